#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace physhand::test {

struct CommandOutput {
    int status = -1;  // the exit code; -1 when it did not run or exit
    std::string out;  // its standard output
};

// Runs `command` in the shell and waits for it.
inline CommandOutput run_command(const std::string& command) {
    CommandOutput output;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return output;
    char buffer[4096];
    while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr) output.out += buffer;
    const int status = pclose(pipe);
    output.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return output;
}

}  // namespace physhand::test
