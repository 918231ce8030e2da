// The in-tree fuzz driver, for builds without libFuzzer: runs a target on every corpus file,
// then on deterministic mutations of them for a bounded time. A crash, an escaping exception or
// an input that takes too long (a hang) saves the input as fuzz-<target>-finding and fails.
//   arbor_fuzz_NAME [--seconds S] [--seed K] [--timeout T] CORPUS_FILE_OR_FOLDER...
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

// The input being run, where the signal handlers can reach it without allocating.
const std::string* g_current = nullptr;
char g_finding_path[512];

void save_current() {
  if (!g_current) return;
  const int fd = ::open(g_finding_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  std::size_t done = 0;
  while (done < g_current->size()) {
    const ssize_t n = ::write(fd, g_current->data() + done, g_current->size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
}

extern "C" void on_fatal_signal(int sig) {
  save_current();
  const char* what = sig == SIGALRM ? "fuzz: an input ran past the time limit (a hang); saved as "
                                    : "fuzz: an input crashed the target; saved as ";
  (void)!::write(2, what, std::strlen(what));
  (void)!::write(2, g_finding_path, std::strlen(g_finding_path));
  (void)!::write(2, "\n", 1);
  if (sig == SIGALRM) _exit(1);
  signal(sig, SIG_DFL);
  raise(sig);
}

// SplitMix64: a small deterministic generator for the mutations.
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
};

// Tokens that reach the parsers' edges: structure, extreme numbers, separators.
const char* const kTokens[] = {"[",
                               "]",
                               "[[",
                               "]]",
                               "{",
                               "}",
                               "(",
                               ")",
                               "=",
                               ";",
                               ":",
                               ",",
                               "\"",
                               "'",
                               "<",
                               ">",
                               "/>",
                               "</",
                               "#",
                               "\n",
                               " ",
                               "\t",
                               "\0",
                               "nan",
                               "inf",
                               "-inf",
                               "1e308",
                               "1e309",
                               "-1",
                               "0",
                               "-0",
                               "0.0",
                               "4294967296",
                               "18446744073709551616",
                               "99999999999999999999999",
                               "1e-320",
                               ".",
                               "..",
                               "-",
                               "f",
                               "v",
                               "vt",
                               "vn",
                               "f 1 2 3",
                               "point",
                               "connect",
                               "branch",
                               "stem",
                               "leaf",
                               "on",
                               "true",
                               "false",
                               "[[tree]]",
                               "[[forest]]",
                               "[output]",
                               "[camera]",
                               "species = ",
                               "model = \"fractal\"",
                               "<param name='Levels' value='3'/>",
                               "iterations",
                               "level=",
                               "number=",
                               "A:",
                               "B(2):"};

std::string mutate(const std::vector<std::string>& corpus, Random& rng) {
  std::string s = corpus[rng.below(corpus.size())];
  const std::size_t steps = 1 + rng.below(8);
  for (std::size_t k = 0; k < steps; ++k) {
    const std::size_t at = rng.below(s.size() + 1);
    switch (rng.below(9)) {
      case 0:  // flip a bit
        if (!s.empty()) s[rng.below(s.size())] ^= static_cast<char>(1u << rng.below(8));
        break;
      case 1:  // a random byte
        s.insert(at, 1, static_cast<char>(rng.below(256)));
        break;
      case 2:  // erase a range
        if (!s.empty()) s.erase(at < s.size() ? at : s.size() - 1, 1 + rng.below(64));
        break;
      case 3: {  // duplicate a range
        const std::size_t len = 1 + rng.below(64);
        if (at < s.size()) s.insert(at, s.substr(at, len));
        break;
      }
      case 4: {  // a token
        const std::string t = kTokens[rng.below(sizeof kTokens / sizeof kTokens[0])];
        s.insert(at, t.empty() ? std::string(1, '\0') : t);
        break;
      }
      case 5: {  // replace a run of digits by an extreme number
        const std::size_t d = s.find_first_of("0123456789", at);
        if (d == std::string::npos) break;
        const std::size_t e = s.find_first_not_of("0123456789.", d);
        const char* extremes[] = {"nan",    "1e309",     "-1", "0", "99999999999999999999999",
                                  "1e-320", "4294967295"};
        s.replace(d, (e == std::string::npos ? s.size() : e) - d, extremes[rng.below(7)]);
        break;
      }
      case 6: {  // splice in a piece of another corpus file
        const std::string& o = corpus[rng.below(corpus.size())];
        const std::size_t from = rng.below(o.size() + 1);
        s.insert(at, o.substr(from, 1 + rng.below(256)));
        break;
      }
      case 7: {  // repeat a short piece many times: deep nesting, long lists
        const std::size_t len = 1 + rng.below(8);
        if (at >= s.size()) break;
        const std::string piece = s.substr(at, len);
        std::string many;
        const std::size_t times = 1 + rng.below(2000);
        for (std::size_t i = 0; i < times && many.size() < 200000; ++i) many += piece;
        s.insert(at, many);
        break;
      }
      default:  // truncate
        s.resize(at);
    }
    if (s.size() > (1u << 20)) s.resize(1u << 20);
  }
  return s;
}

void add_file(const std::string& path, std::vector<std::string>& corpus) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  if (in) corpus.push_back(ss.str());
}

void add_path(const std::string& path, std::vector<std::string>& corpus) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    std::fprintf(stderr, "fuzz: no such corpus file or folder: %s\n", path.c_str());
    std::exit(2);
  }
  if (!S_ISDIR(st.st_mode)) return add_file(path, corpus);
  DIR* d = ::opendir(path.c_str());
  std::vector<std::string> names;
  while (dirent* e = d ? ::readdir(d) : nullptr) {
    if (e->d_name[0] != '.') names.emplace_back(e->d_name);
  }
  if (d) ::closedir(d);
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) add_file(path + "/" + n, corpus);
}

bool run_one(const std::string& input) {
  g_current = &input;
  try {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  } catch (const std::exception& e) {
    save_current();
    std::fprintf(stderr, "fuzz: an exception escaped the target (%s); saved as %s\n", e.what(),
                 g_finding_path);
    return false;
  } catch (...) {
    save_current();
    std::fprintf(stderr, "fuzz: an exception escaped the target; saved as %s\n", g_finding_path);
    return false;
  }
  g_current = nullptr;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0;
  std::uint64_t seed = 1;
  unsigned timeout = 10;
  std::vector<std::string> corpus;
  std::string name = argv[0];
  name = name.substr(name.find_last_of('/') + 1);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seconds" && i + 1 < argc)
      seconds = std::atof(argv[++i]);
    else if (a == "--seed" && i + 1 < argc)
      seed = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--timeout" && i + 1 < argc)
      timeout = static_cast<unsigned>(std::atoi(argv[++i]));
    else
      add_path(a, corpus);
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "usage: %s [--seconds S] [--seed K] [--timeout T] CORPUS...\n",
                 name.c_str());
    return 2;
  }
  std::snprintf(g_finding_path, sizeof g_finding_path, "fuzz-%s-finding", name.c_str());
  for (const int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGALRM})
    signal(sig, on_fatal_signal);
  // The stack of a crash by overflow needs a stack of its own to run the handler on.
  static char alternate[1 << 16];
  stack_t ss{};
  ss.ss_sp = alternate;
  ss.ss_size = sizeof alternate;
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sa.sa_flags = SA_ONSTACK;
  sigaction(SIGSEGV, &sa, nullptr);

  const auto start = std::chrono::steady_clock::now();
  std::uint64_t runs = 0;
  Random rng{seed};
  for (const std::string& input : corpus) {
    alarm(timeout);
    if (!run_one(input)) return 1;
    ++runs;
  }
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  while (elapsed() < seconds) {
    const std::string input = mutate(corpus, rng);
    alarm(timeout);
    if (!run_one(input)) return 1;
    ++runs;
  }
  alarm(0);
  std::printf("fuzz %s: %llu executions in %.1f s (%zu corpus files, seed %llu), no findings\n",
              name.c_str(), static_cast<unsigned long long>(runs), elapsed(), corpus.size(),
              static_cast<unsigned long long>(seed));
  return 0;
}
