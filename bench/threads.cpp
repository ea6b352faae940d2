// How the fast operator of section 4 scales from one thread to two, on the paper's cube (31):
// setup (cluster frames, coverings (42), near field (43), far coefficients (44)-(45) when stored)
// and the product K_n v (43), timed in pairs inside one process. A pair is three runs back to
// back, their order rotated from pair to pair: one thread on the first processor, one thread on
// the second, and two threads, one on each (every thread pinned). A virtual machine's speed
// drifts from one minute to the next (other work on the same processors and memory); a pair sees
// the same drift, so the ratio of a pair, the faster lone processor's time over the two
// threads' time, measures the threads, and the median over pairs is quoted with the least and
// greatest pair. Other work may also share the core under one processor for seconds
// at a time, slowing that processor alone: the lone runs on each processor give each pair its
// own ceiling, t / t_0 + t / t_1 with t the lesser of the two lone times t_0, t_1 (the speed-up
// of perfectly divided work on those two processors as they ran), and the pair's ratio over it
// is the code's share. Beside them: the ratio of the least times of one thread and of two (the
// machine's noise only adds time, so the least of K runs is the least disturbed). Each pair also
// checks that every placement gives the same bits: the operators set up on each, applied on each.
//   - Setup: the operator before is released first. Its chunks (the near and far lists, the
//     arrays of 256 KiB or more, the stored coefficients) stay with the process (ChunkPool, up to
//     its limit, a sixteenth of the memory available) and the next setup writes there; its
//     smaller arrays are reused as far as the allocator keeps them. The pages touched for the
//     first time are counted (minor page faults). --keep-memory has the allocator keep all freed
//     memory too. The first setup of a process, on memory new to it, is bench/product's.
//   - Product: on the last operator set up, one product on each placement first (the product's
//     workspace), then --pairs K pairs.
//   - The time taken from this machine by other work (steal, /proc/stat) during the runs of
//     each thread count, where the system reports it.
//   - Before each pair, the machine's own ceiling (two_thread_ceiling): the speed-up that a fixed
//     arithmetic workload gets from two threads at that moment, and each pair's ratio against it;
//     the same for streaming memory (each thread summing an array of its own twice the size of
//     the last-level cache), so that a pair's ratio can be read against what the memory
//     system allowed two threads at that moment; before each setup pair also the first-touch
//     ceiling, the same for touching new memory.
//   usage: threads [--level L] [--pairs K] [--setup-pairs K] [--keep-memory] [--unpinned]
//                  [--double | --single] [--recompute] [--setting ETA M]...
// Default: level 6 (n = 49,152), (0.5, 7), coefficients stored or not as the library chooses,
// 9 product pairs, 5 setup pairs. --unpinned leaves the threads where the system puts them, as in
// a user's run (the two lone runs then are two one-thread runs anywhere); so does a process
// allowed fewer than two processors.
#include "fast_settings.hpp"
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <malloc.h>
#include <omp.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>

using namespace panelrad;

namespace {

using bench::median;

// Ticks of all CPUs and of steal (time given to other work) from the "cpu" line of
// /proc/stat; {0, 0} where that file is not there.
struct CpuTicks {
  unsigned long long total = 0, steal = 0;
};

CpuTicks cpu_ticks() {
  std::ifstream in("/proc/stat");
  std::string name;
  CpuTicks t;
  if (!(in >> name) || name != "cpu") return t;
  unsigned long long field = 0;
  for (int k = 0; k < 10 && in >> field; ++k) {
    t.total += field;
    if (k == 7) t.steal = field;
  }
  return t;
}

// Pages this process has touched for the first time (minor page faults), all threads.
long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// A fixed arithmetic workload: independent chains of multiply-adds in registers, no memory (one
// function, not inlined, so that every caller runs the same code; the count is read at run time).
volatile long arithmetic_iterations = 4'000'000;

[[gnu::noinline]] double arithmetic_work() {
  double x[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const long iterations = arithmetic_iterations;
  for (long i = 0; i < iterations; ++i)
    for (double& xj : x) xj = xj * 0.999999 + 1e-3;
  double sum = 0;
  for (const double xj : x) sum += xj;
  return sum;
}

// Memory new to the process, first touched: 16 MiB mapped, one byte written per 4 KiB page (a
// page fault each, the kernel zeroing the page and, in a virtual machine, the hypervisor backing it),
// unmapped. The workload of the first-touch ceiling.
double first_touch_work() {
  constexpr std::size_t kBytes = std::size_t{16} << 20, kPage = 4096;
  void* p = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return 0;
  volatile char* bytes = static_cast<volatile char*>(p);
  for (std::size_t at = 0; at < kBytes; at += kPage) bytes[at] = 1;
  const double first = bytes[0];
  munmap(p, kBytes);
  return first;
}

// Memory streamed: the calling thread sums an array of its own, 64 MiB (twice this machine's
// 32 MiB last-level cache, so that every pass reads main memory), with eight partial sums so that
// the reads, not the additions, set the pace. The arrays are filled once, by
// prepare_streaming_work, before any timing.
double streaming_work() {
  thread_local std::vector<double> data;
  if (data.empty()) data.assign(std::size_t{8} << 20, 1.0);
  double sum[8] = {};
  for (std::size_t i = 0; i < data.size(); i += 8)
    for (int j = 0; j < 8; ++j) sum[j] += data[i + static_cast<std::size_t>(j)];
  double total = 0;
  for (const double s : sum) total += s;
  return total;
}

void prepare_streaming_work() {
  static volatile double sink = 0;
#pragma omp parallel num_threads(2)
  {
    const double r = streaming_work();
#pragma omp critical(panelrad_bench_streaming)
    sink = sink + r;
  }
}

// The processors this process may run on (its affinity mask), in order.
std::vector<int> allowed_processors() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> cpus;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

// Where a run's threads are: the first processor alone, the second alone, or both.
enum Placement { kFirstAlone = 0, kSecondAlone = 1, kBoth = 2 };

// Whether every pinning so far took effect (the system may refuse a processor).
std::atomic<bool> pinning_held{true};

void pin_calling_thread(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  if (pthread_setaffinity_np(pthread_self(), sizeof set, &set) != 0) pinning_held = false;
}

// Sets the thread count of the library's parallel regions and pins their threads: the calling
// thread (OpenMP's thread 0) alone on cpus[0] or cpus[1], or thread t of two on cpus[t] (OpenMP
// keeps its threads from region to region, so the pinning holds for the run). Unpinned with
// fewer than two processors.
void place(Placement where, const std::vector<int>& cpus) {
  const int threads = where == kBoth ? 2 : 1;
  set_threads(threads);
  if (cpus.size() < 2) return;
  if (where != kBoth) {
    pin_calling_thread(cpus[static_cast<std::size_t>(where)]);
    return;
  }
#pragma omp parallel num_threads(2)
  pin_calling_thread(cpus[static_cast<std::size_t>(omp_get_thread_num() & 1)]);
}

// What the machine itself allows two threads at this moment for a workload: timed on one thread
// alone (t), then on two threads at once, each timing its own copy (t_0, t_1), three times, the
// medians taken; the ceiling t / t_0 + t / t_1 is the speed-up of perfectly divided work. For
// arithmetic it is 2 when both processors run at full speed, less when other work shares
// the core under one of them; for first touches it is what the kernel's (and the
// hypervisor's) page faults allow two threads of one process.
template <class Work>
double two_thread_ceiling(Work work) {
  static volatile double sink = 0;
  std::vector<double> alone, t[2];
  for (int round = 0; round < 3; ++round) {
    Stopwatch clock;
    sink = work();
    alone.push_back(clock.seconds());
#pragma omp parallel num_threads(2)
    {
      Stopwatch own;
      const double r = work();
      const double seconds = own.seconds();
#pragma omp critical(panelrad_bench_ceiling)
      {
        sink = sink + r;
        t[omp_get_thread_num() & 1].push_back(seconds);
      }
    }
  }
  if (t[1].empty()) return 1.0;  // the team had one thread
  return median(alone) / median(t[0]) + median(alone) / median(t[1]);
}

// The timed runs of one thread count: seconds, and the ticks they took.
struct Runs {
  std::vector<double> seconds, faults;
  CpuTicks ticks;
  template <class F>
  void time(F&& run) {
    const CpuTicks before = cpu_ticks();
    const long faults_before = minor_faults();
    Stopwatch clock;
    run();
    seconds.push_back(clock.seconds());
    faults.push_back(static_cast<double>(minor_faults() - faults_before));
    const CpuTicks after = cpu_ticks();
    ticks.total += after.total - before.total;
    ticks.steal += after.steal - before.steal;
  }
  void add(const Runs& other) {
    seconds.insert(seconds.end(), other.seconds.begin(), other.seconds.end());
    faults.insert(faults.end(), other.faults.begin(), other.faults.end());
    ticks.total += other.ticks.total;
    ticks.steal += other.ticks.steal;
  }
  std::string steal() const {
    if (ticks.total == 0) return "n/a";
    char s[32];
    std::snprintf(s, sizeof s, "%.1f%%", 100.0 * static_cast<double>(ticks.steal) / static_cast<double>(ticks.total));
    return s;
  }
};

// The pairs' times: runs[p] is every pair's time with placement p; pair k's one-thread time is
// the faster lone processor's.
void report(const char* what, const Runs (&runs)[3], const std::vector<double>& ceiling,
            const std::vector<double>& streaming_ceiling, const std::vector<double>& touch_ceiling) {
  const Runs& two = runs[kBoth];
  std::vector<double> one, ratio, own_ceiling, own_efficiency, efficiency;
  for (std::size_t k = 0; k < two.seconds.size(); ++k) {
    const double t0 = runs[kFirstAlone].seconds[k], t1 = runs[kSecondAlone].seconds[k];
    one.push_back(std::min(t0, t1));
    ratio.push_back(one.back() / two.seconds[k]);
    own_ceiling.push_back(one.back() / t0 + one.back() / t1);
    own_efficiency.push_back(ratio.back() / own_ceiling.back());
    efficiency.push_back(ratio.back() / ceiling[k]);
  }
  Runs alone = runs[kFirstAlone];  // steal and new pages of one thread: both lone placements
  alone.add(runs[kSecondAlone]);
  const auto [lo, hi] = std::minmax_element(ratio.begin(), ratio.end());
  std::printf("  %-8s median %.4f / %.4f s = %.2fx; pairs: median %.2fx, range %.2f-%.2fx (%zu); steal %s / %s; "
              "new pages %.1f / %.1f MB\n",
              what, median(one), median(two.seconds), median(one) / median(two.seconds), median(ratio), *lo, *hi,
              ratio.size(), alone.steal().c_str(), two.steal().c_str(), median(alone.faults) * 4096e-6,
              median(two.faults) * 4096e-6);
  // The least time of each thread count: the machine's noise only ever adds time (other work,
  // steal), so the least of K runs is the estimate least disturbed by it.
  const double best_one = *std::min_element(one.begin(), one.end());
  const double best_two = *std::min_element(two.seconds.begin(), two.seconds.end());
  std::printf("  %-8s best of %zu: %.4f / %.4f s = %.2fx\n", "", one.size(), best_one, best_two, best_one / best_two);
  const auto [olo, ohi] = std::minmax_element(own_ceiling.begin(), own_ceiling.end());
  const auto [elo, ehi] = std::minmax_element(own_efficiency.begin(), own_efficiency.end());
  std::printf("  %-8s each processor alone: median %.4f / %.4f s; the pairs' own ceiling median %.2fx (%.2f-%.2fx); "
              "pair / its own ceiling: median %.2f (%.2f-%.2f)\n",
              "", median(runs[kFirstAlone].seconds), median(runs[kSecondAlone].seconds), median(own_ceiling), *olo, *ohi,
              median(own_efficiency), *elo, *ehi);
  // The pairs whose processors ran alone at nearly one speed (own ceiling >= 1.9x: within about
  // 10% of each other): what two threads give where the machine gave two whole processors.
  std::vector<double> even;
  for (std::size_t k = 0; k < ratio.size(); ++k)
    if (own_ceiling[k] >= 1.9) even.push_back(ratio[k]);
  if (even.empty()) {
    std::printf("  %-8s pairs with an own ceiling >= 1.90x: none of %zu\n", "", ratio.size());
  } else {
    const auto [vlo, vhi] = std::minmax_element(even.begin(), even.end());
    std::printf("  %-8s pairs with an own ceiling >= 1.90x: %zu of %zu, median %.2fx, range %.2f-%.2fx\n", "",
                even.size(), ratio.size(), median(even), *vlo, *vhi);
  }
  const auto [clo, chi] = std::minmax_element(ceiling.begin(), ceiling.end());
  std::printf("  %-8s machine's ceiling median %.2fx (%.2f-%.2fx); pair / its ceiling: median %.2f", "", median(ceiling),
              *clo, *chi, median(efficiency));
  const auto [slo, shi] = std::minmax_element(streaming_ceiling.begin(), streaming_ceiling.end());
  std::printf("; streaming ceiling median %.2fx (%.2f-%.2fx)", median(streaming_ceiling), *slo, *shi);
  if (touch_ceiling.empty()) {
    std::printf("\n");
  } else {
    const auto [tlo, thi] = std::minmax_element(touch_ceiling.begin(), touch_ceiling.end());
    std::printf("; first-touch ceiling median %.2fx (%.2f-%.2fx)\n", median(touch_ceiling), *tlo, *thi);
  }
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  int level = 6, pairs = 9, setup_pairs = 5;
  bool keep_memory = false, unpinned = false;
  bench::FastSettings fast;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--level") && i + 1 < argc) {
      level = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--pairs") && i + 1 < argc) {
      pairs = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--setup-pairs") && i + 1 < argc) {
      setup_pairs = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--keep-memory")) {
      keep_memory = true;
    } else if (!std::strcmp(argv[i], "--unpinned")) {
      unpinned = true;
    } else if (!fast.parse(i, argc, argv)) {
      std::cerr << "usage: threads [--level L] [--pairs K] [--setup-pairs K] [--keep-memory] [--unpinned] "
                   "[--double | --single] "
                   "[--recompute] [--setting ETA M]...\n";
      return 2;
    }
  }
  if (fast.settings.empty()) fast.settings = {{0.5, 7}};
  // glibc maps each block above 32 MiB on its own and returns it when freed, so such arrays are
  // new memory to every setup; kept, all of them are served from the heap and stay there.
  if (keep_memory && !(mallopt(M_MMAP_MAX, 0) && mallopt(M_TRIM_THRESHOLD, INT_MAX))) {
    std::cerr << "threads: --keep-memory: the allocator refused the settings\n";
    return 2;
  }
  try {
    const Scene cube = make_paper_cube_scene();
    const Collocation col(cube, level);
    prepare_streaming_work();
    std::printf("one thread against two on the cube, level %d, n = %d (hardware threads: %u)%s\n", level,
                static_cast<int>(col.size()), std::thread::hardware_concurrency(),
                keep_memory ? "; memory kept by the allocator between setups" : "");
    const std::vector<int> cpus = unpinned ? std::vector<int>{} : allowed_processors();
    if (unpinned)
      std::printf("threads not pinned (--unpinned): the two lone runs are one-thread runs wherever the system puts them\n");
    else if (cpus.size() >= 2)
      std::printf("threads pinned: one thread on processor %d, then on %d; two threads on %d and %d\n", cpus[0], cpus[1],
                  cpus[0], cpus[1]);
    else
      std::printf("one processor allowed: threads not pinned, the two lone runs on the same processor\n");
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(col.size(), 0.25, 1.0);
    for (const auto& [eta, degree] : fast.settings) {
      const FastOptions o = fast.options(eta, degree);
      Runs setup[3], product[3];  // per Placement
      std::vector<double> setup_ceiling, product_ceiling, touch_ceiling;  // two_thread_ceiling before each pair
      std::vector<double> setup_streaming, product_streaming;
      std::vector<double> stage[3][4];  // per Placement: geometry, targets, coverings, far (FastStatistics)
      bool identical = true;
      Eigen::VectorXd reference;  // the product of the first operator, on one thread
      Eigen::VectorXd y = Eigen::VectorXd::Zero(col.size());  // allocated before any timing
      const auto apply = [&](const FastOperator& op, Placement where, Runs* runs) {
        place(where, cpus);
        if (runs) runs->time([&] { op.apply(v, y); });
        else op.apply(v, y);
        if (reference.size() == 0) reference = y;
        identical = identical && same_bits(y, reference);
      };
      const auto ceilings = [&](std::vector<double>& arithmetic, std::vector<double>& streaming) {
        place(kBoth, cpus);  // the lone workload on the first processor
        arithmetic.push_back(two_thread_ceiling(arithmetic_work));
        streaming.push_back(two_thread_ceiling(streaming_work));
      };
      std::unique_ptr<FastOperator> op;
      for (int pair = 0; pair < setup_pairs; ++pair) {
        ceilings(setup_ceiling, setup_streaming);
        touch_ceiling.push_back(two_thread_ceiling(first_touch_work));
        for (int k = 0; k < 3; ++k) {
          const Placement where = static_cast<Placement>((pair + k) % 3);
          op.reset();  // every setup finds the allocator as the one before it left it
          place(where, cpus);
          setup[where].time([&] { op = std::make_unique<FastOperator>(col, o); });
          const FastStatistics& st = op->statistics();
          for (std::size_t j = 0; const double s : {st.geometry_s, st.targets_s, st.covering_s, st.far_s})
            stage[where][j++].push_back(s);
          apply(*op, where, nullptr);  // the same bits as the other placements' operators
        }
      }
      for (const Placement where : {kFirstAlone, kSecondAlone, kBoth}) apply(*op, where, nullptr);  // workspace
      for (int pair = 0; pair < pairs; ++pair) {
        ceilings(product_ceiling, product_streaming);
        for (int k = 0; k < 3; ++k) {
          const Placement where = static_cast<Placement>((pair + k) % 3);
          apply(*op, where, &product[where]);
        }
      }
      const FastStatistics& s = op->statistics();
      std::printf("(%.2f, M %d), coefficients %s, %zu far pairs, %.1f MB held\n", eta, degree,
                  !s.far_stored ? "recomputed" : o.single_precision_coefficients ? "float, stored" : "double, stored",
                  s.far_pairs, static_cast<double>(op->bytes()) / 1e6);
      report("setup", setup, setup_ceiling, setup_streaming, touch_ceiling);
      std::printf("  stages, median first processor alone / both:");
      for (std::size_t k = 0; const char* name : {"geometry", "targets", "coverings", "far"}) {
        std::printf(" %s %.4f / %.4f s%s", name, median(stage[kFirstAlone][k]), median(stage[kBoth][k]),
                    k < 3 ? "," : "\n");
        ++k;
      }
      report("product", product, product_ceiling, product_streaming, {});
      if (!pinning_held)
        std::printf("  pinning failed at least once: the system refused a processor, so some runs were not pinned\n");
      std::printf("  bit-identical products (operators set up and applied on each placement): %s\n",
                  identical ? "yes" : "NO");
      std::fflush(stdout);
      if (!identical) return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "threads: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
