// main() for the fuzz targets where libFuzzer is not available (GCC): feeds
// LLVMFuzzerTestOneInput every file of the corpus, then a fixed number of seeded mutations
// of each, so the default test suite still runs every target and replays the crash
// regressions kept in the corpus. The same build, arguments and files give the same inputs.
//
// Usage: TARGET [--mutations N] PATH...   (PATH: a file, or a folder of files)

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

constexpr std::size_t kDefaultMutations = 500;
constexpr int kMaxEditsPerMutation = 4;
// Bytes that change the structure of JSON text, or the sign, size or kind of a number.
constexpr std::array<std::uint8_t, 16> kInterestingBytes = {
    0x00, 0xff, 0x80, 0x7f, '"', '{', '}', '[', ']', ',', ':', '-', '0', '9', 'e', '.'};

Bytes read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t below(std::mt19937_64& rng, std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

// One to kMaxEditsPerMutation of the edits libFuzzer starts from: a bit flip, a truncation,
// an inserted byte, an overwritten byte, a copied span.
Bytes mutate(Bytes data, std::mt19937_64& rng) {
    const int edits = 1 + static_cast<int>(below(rng, kMaxEditsPerMutation));
    for (int e = 0; e < edits; ++e) {
        const auto interesting = [&] {
            return kInterestingBytes[below(rng, kInterestingBytes.size())];
        };
        if (data.empty()) {
            data.push_back(interesting());
            continue;
        }
        const std::size_t at = below(rng, data.size());
        switch (below(rng, 5)) {
            case 0:
                data[at] ^= static_cast<std::uint8_t>(1u << below(rng, 8));
                break;
            case 1:
                data.resize(at);
                break;
            case 2:
                data.insert(data.begin() + static_cast<std::ptrdiff_t>(at), interesting());
                break;
            case 3:
                data[at] = interesting();
                break;
            default: {
                const std::size_t length =
                    1 + below(rng, std::min<std::size_t>(data.size() - at, 64));
                const Bytes span(data.begin() + static_cast<std::ptrdiff_t>(at),
                                 data.begin() + static_cast<std::ptrdiff_t>(at + length));
                const std::size_t to = below(rng, data.size() + 1);
                data.insert(data.begin() + static_cast<std::ptrdiff_t>(to), span.begin(),
                            span.end());
                break;
            }
        }
    }
    return data;
}

void run(const Bytes& input) {
    LLVMFuzzerTestOneInput(input.data(), input.size());
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t mutations = kDefaultMutations;
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--mutations" && i + 1 < argc) {
            mutations = std::stoul(argv[++i]);
        } else if (fs::is_directory(arg)) {
            for (const auto& entry : fs::directory_iterator(arg)) {
                if (entry.is_regular_file()) files.push_back(entry.path());
            }
        } else if (fs::is_regular_file(arg)) {
            files.emplace_back(arg);
        } else {
            std::fprintf(stderr, "%s: no file or folder %s\n", argv[0], argv[i]);
            return 2;
        }
    }
    if (files.empty()) {
        std::fprintf(stderr, "usage: %s [--mutations N] FILE_OR_FOLDER...\n", argv[0]);
        return 2;
    }
    std::sort(files.begin(), files.end());  // directory order differs between file systems

    std::size_t inputs = 0;
    for (std::size_t f = 0; f < files.size(); ++f) {
        const Bytes original = read_file(files[f]);
        run(original);
        std::mt19937_64 rng(f);
        for (std::size_t m = 0; m < mutations; ++m) run(mutate(original, rng));
        inputs += 1 + mutations;
    }
    std::printf("%s: %zu inputs from %zu files, no crash\n", argv[0], inputs, files.size());
    return 0;
}
