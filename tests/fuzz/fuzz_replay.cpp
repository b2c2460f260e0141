// Runs the fuzz target without libFuzzer (any compiler): every file given on the command line,
// plus a fixed set of deterministic mutations of each (bit flips, byte changes, truncations,
// duplicated spans). Registered with ctest, so the target is exercised in every build, and under
// the sanitizers in the sanitizer build. scripts/fuzz.sh runs the real libFuzzer with clang.

#include <cstdint>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  std::mt19937_64 rng(12345);
  long runs = 0;
  for (int a = 1; a < argc; ++a) {
    std::ifstream in(argv[a], std::ios::binary);
    const std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (seed.empty()) continue;
    auto run = [&](const std::string& s) {
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
      ++runs;
    };
    run(seed);
    for (int m = 0; m < 200; ++m) {
      std::string s = seed;
      std::uniform_int_distribution<std::size_t> pos(0, s.size() - 1);
      switch (m % 5) {
        case 0: s[pos(rng)] ^= static_cast<char>(1u << (rng() % 8)); break;
        case 1: s[pos(rng)] = static_cast<char>(rng()); break;
        case 2: s.resize(pos(rng)); break;
        case 3: {
          const std::size_t p = pos(rng);
          s.insert(p, s.substr(p, 1 + rng() % 64));
          break;
        }
        case 4:
          for (int k = 0; k < 8; ++k) s[pos(rng)] = "0123456789 -.e\n/#fv"[rng() % 19];
          break;
      }
      run(s);
    }
  }
  std::cout << runs << " inputs ran through the target without a crash\n";
  return 0;
}
