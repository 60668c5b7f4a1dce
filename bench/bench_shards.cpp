// Times a study split into shards (deb uncertainty --shard K/N, then deb
// merge) against the same study in one process, and prints the parallel
// efficiency: P shard processes of one thread each run at once, then one
// merge; efficiency = T(1 process, 1 thread) / (P x T(P shards + merge)).
// On a machine with fewer cores than P the shards share them
// (oversubscribed): the figure then says what the split costs, not what
// it gains. Also prints the merge alone (the serial part: reading the
// parts, the statistics and the report) and the bytes of the parts.
// With MPI (DEB_MPI), the same study under mpirun with 1, 2 and 4
// evaluating ranks.
// Usage: bench_shards [BUDGET.yaml SAMPLES]   (default: the thesis with
// tolerances, 10000 samples; then the metrology frame's, 500 samples)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs a shell command line (deb's own arguments only), timed; exits on failure.
double Timed(const std::string& line) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::system(line.c_str()) != 0) {
    std::fprintf(stderr, "bench_shards: failed: %s\n", line.c_str());
    std::exit(1);
  }
  return Seconds(t0);
}

void Study(const std::string& budget, int samples, const fs::path& work) {
  const std::string deb = "'" + std::string(DEB_BINARY) + "'";
  const std::string study = deb + " uncertainty '" + budget + "' -n " + std::to_string(samples) + " -q --no-plots --force";
  std::printf("%s, %d samples, --no-plots\n", fs::path(budget).filename().c_str(), samples);
  const double one = Timed(study + " -j 1 --out '" + (work / "one").string() + "'");
  std::printf("  1 process, 1 thread:  %6.2f s\n", one);
  const double two = Timed(study + " -j 2 --out '" + (work / "two").string() + "'");
  std::printf("  1 process, 2 threads: %6.2f s (efficiency %.2f)\n", two, one / (2 * two));
  for (int p : {2, 4}) {
    std::string line;
    for (int k = 1; k <= p; ++k)
      line += study + " -j 1 --shard " + std::to_string(k) + "/" + std::to_string(p) + " --out '" +
              (work / ("part" + std::to_string(k))).string() + "' & ";
    const double shards = Timed("sh -c \"" + line + "wait\"");
    std::string parts;
    std::uintmax_t bytes = 0;
    for (int k = 1; k <= p; ++k) {
      const fs::path part = work / ("part" + std::to_string(k));
      parts += " '" + part.string() + "'";
      bytes += fs::file_size(part / "part.json");
    }
    const double merge = Timed(deb + " merge" + parts + " -q --no-plots --force --out '" + (work / "merged").string() + "'");
    const bool same = std::system(("cmp -s '" + (work / "two" / "summary.json").string() + "' '" +
                                   (work / "merged" / "summary.json").string() + "'").c_str()) == 0;
    std::printf("  %d shards at once:    %6.2f s + merge %.2f s = %.2f s (efficiency %.2f%s); parts %.1f MB; "
                "summary.json %s\n",
                p, shards, merge, shards + merge, one / (p * (shards + merge)),
                p > 2 ? ", oversubscribed on 2 cores" : "", static_cast<double>(bytes) / 1e6,
                same ? "identical" : "DIFFERS");
    for (int k = 1; k <= p; ++k) fs::remove_all(work / ("part" + std::to_string(k)));
  }
  // Under mpirun: P evaluating ranks and rank 0, which hands out the blocks.
  const std::string mpiexec = DEB_MPIEXEC;
  if (mpiexec.empty()) {
    std::printf("  (deb built without MPI: no mpirun figures)\n");
    return;
  }
  for (int p : {1, 2, 4}) {
    const std::string root = ::geteuid() == 0 ? " --allow-run-as-root" : "";
    const double t = Timed("'" + mpiexec + "' --oversubscribe" + root + " -n " + std::to_string(p + 1) + " " + study +
                           " -j 1 --out '" + (work / "ranks").string() + "'");
    const bool same = std::system(("cmp -s '" + (work / "two" / "summary.json").string() + "' '" +
                                   (work / "ranks" / "summary.json").string() + "'").c_str()) == 0;
    std::printf("  mpirun, %d evaluating rank(s) + rank 0: %6.2f s (efficiency %.2f%s); summary.json %s\n", p, t,
                one / (p * t), p > 2 ? ", oversubscribed" : "", same ? "identical" : "DIFFERS");
  }
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path work = fs::temp_directory_path() / ("deb_bench_shards_" + std::to_string(::getpid()));
  fs::create_directories(work);
  if (argc > 2) {
    Study(argv[1], std::atoi(argv[2]), work);
  } else {
    Study(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_tolerances.yaml", 10000, work);
    Study(std::string(DEB_SOURCE_DIR) + "/budgets/metrology_frame_tolerances.yaml", 500, work);
  }
  fs::remove_all(work);
  return 0;
}
