// uwbsar_load: CPU (and optionally memory-bandwidth) load for tests and benchmarks, so
// that live results can be checked on a busy machine: one busy thread per core
// (or --threads N) spinning on integer work, and with --memory-mib M one more thread per
// 4 cores streaming copies through an M MiB buffer (evicting the caches, taking memory
// bandwidth). Runs --seconds S (0: until SIGINT/SIGTERM). Prints one line at start.
// Usage: uwbsar_load [--threads N] [--memory-mib M] [--seconds S]
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop = true; }

void Spin() {
  std::uint64_t x = 88172645463325252ULL;
  while (!g_stop.load(std::memory_order_relaxed)) {
    for (int i = 0; i < 100000; ++i) {  // xorshift: no memory traffic
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
    }
  }
  if (x == 42) std::printf("%llu\n", static_cast<unsigned long long>(x));  // keep the work
}

void StreamMemory(std::size_t bytes) {
  std::vector<char> a(bytes / 2, 1), b(bytes / 2, 2);
  while (!g_stop.load(std::memory_order_relaxed)) {
    std::memcpy(a.data(), b.data(), a.size());
    std::memcpy(b.data(), a.data(), b.size());
  }
}

int Usage(const char* why) {
  std::fprintf(stderr,
               "uwbsar_load: %s\nusage: uwbsar_load [--threads N] [--memory-mib M] "
               "[--seconds S]\n",
               why);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = static_cast<int>(std::thread::hardware_concurrency());
  if (threads <= 0) threads = 1;
  long memory_mib = 0;
  double seconds = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return Usage(("missing value after " + arg).c_str());
    char* end = nullptr;
    const double v = std::strtod(argv[++i], &end);
    if (end == argv[i] || *end != '\0' || v < 0) return Usage(("bad value for " + arg).c_str());
    if (arg == "--threads") {
      threads = static_cast<int>(v);
    } else if (arg == "--memory-mib") {
      memory_mib = static_cast<long>(v);
    } else if (arg == "--seconds") {
      seconds = v;
    } else {
      return Usage(("unknown option " + arg).c_str());
    }
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const int hogs = memory_mib > 0 ? std::max(1, threads / 4) : 0;
  std::printf("uwbsar_load: %d busy threads, %d memory threads over %ld MiB, %s\n", threads, hogs,
              memory_mib, seconds > 0 ? (std::to_string(seconds) + " s").c_str() : "until stopped");
  std::fflush(stdout);
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(Spin);
  for (int i = 0; i < hogs; ++i) {
    pool.emplace_back(StreamMemory, static_cast<std::size_t>(memory_mib) * 1024 * 1024);
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!g_stop) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (seconds > 0 && std::chrono::steady_clock::now() >= end) g_stop = true;
  }
  for (std::thread& t : pool) t.join();
  return 0;
}
