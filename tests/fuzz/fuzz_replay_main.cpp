// Replay driver for fuzz targets when libFuzzer is not in use (g++ builds).
//
// Runs LLVMFuzzerTestOneInput on every file of the seed corpus folders given
// on the command line, then on kMutationsPerSeed deterministic mutations of
// each (byte flips, truncations, insertions of boundary bytes, splices), so a
// plain test run still feeds every parser thousands of malformed inputs.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

constexpr int kMutationsPerSeed = 2000;
constexpr uint8_t kBoundaryBytes[] = {0x00, 0xff, 0x7f, 0x80, '"', '{', '}', '[', ']',
                                      ',',  ':',  '-',  '.',  'e', '\n', ' ', '9', '$'};

std::vector<uint8_t> readFile(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

void run(const std::vector<uint8_t>& input) { LLVMFuzzerTestOneInput(input.data(), input.size()); }

std::vector<uint8_t> mutate(std::vector<uint8_t> input, const std::vector<uint8_t>& other,
                            std::mt19937& random) {
  const int edits = 1 + static_cast<int>(random() % 4);
  for (int edit = 0; edit < edits; ++edit) {
    const size_t at = input.empty() ? 0 : random() % (input.size() + 1);
    switch (random() % 5) {
      case 0:
        if (at < input.size()) input[at] ^= static_cast<uint8_t>(1u << (random() % 8));
        break;
      case 1:
        input.resize(at);
        break;
      case 2:
        input.insert(input.begin() + at, kBoundaryBytes[random() % sizeof(kBoundaryBytes)]);
        break;
      case 3:
        if (at < input.size()) input.erase(input.begin() + at);
        break;
      default:
        if (!other.empty()) {
          const size_t from = random() % other.size();
          input.insert(input.begin() + at, other.begin() + from,
                       other.begin() + std::min(other.size(), from + 1 + random() % 64));
        }
    }
  }
  return input;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::vector<uint8_t>> seeds = {{}};
  for (int i = 1; i < argc; ++i) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(argv[i])) {
      if (entry.is_regular_file()) {
        seeds.push_back(readFile(entry.path()));
      }
    }
  }
  std::mt19937 random(20261122u);
  for (const auto& seed : seeds) {
    run(seed);
    for (int m = 0; m < kMutationsPerSeed; ++m) {
      run(mutate(seed, seeds[random() % seeds.size()], random));
    }
  }
  std::printf("fuzz replay: %zu seeds, %zu inputs, no crash\n", seeds.size(),
              seeds.size() * (1 + kMutationsPerSeed));
  return 0;
}
