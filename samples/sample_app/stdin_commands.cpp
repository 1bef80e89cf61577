#include "stdin_commands.h"

#include <poll.h>
#include <unistd.h>

#include <string>
#include <utility>

namespace physhand::sample {

UserCommand poll_user_command() {
    // Characters of a line not yet ended.
    static std::string pending;
    pollfd input{STDIN_FILENO, POLLIN, 0};
    while (poll(&input, 1, 0) == 1 && (input.revents & POLLIN) != 0) {
        char c = 0;
        if (read(STDIN_FILENO, &c, 1) != 1) break;
        if (c != '\n') {
            pending += c;
            continue;
        }
        const std::string line = std::exchange(pending, {});
        if (line == "r") return UserCommand::Reset;
        if (line == "n") return UserCommand::Next;
        if (line == "q") return UserCommand::Quit;
    }
    return UserCommand::None;
}

}  // namespace physhand::sample
