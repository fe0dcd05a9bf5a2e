// `gyrotherm score` campaigns: 10 trials of the simulated cycle
// (scenarios/cycle.toml) with every engine, each trial simulated once,
// prepared once and fitted by all engines (studies/score/campaign.h). Wall-clock time,
// since threads are the point.
//  BM_Campaign/<threads>: the campaign on 1 and 2 threads.
//  BM_CampaignSpeedup: both in each iteration; counters seconds_1_thread,
//    seconds_2_threads and speedup = their ratio (the aim: ≥ 1.8),
//    and `ceiling`: the same ratio for a pure arithmetic loop split over 1
//    and 2 threads, measured in the same iteration: what the machine itself
//    offers at that moment (below 2 when other work shares the cores).
//  BM_CampaignScaling/<trials>: 100, 1,000 and 10,000 trials on 2 threads,
//    once each (the largest takes about a minute and a half): ms_per_trial
//    stays the same if campaign time grows linearly with the trials.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "studies/score/baseline.h"
#include "studies/score/campaign.h"
#include "studies/score/outcome_packing.h"
#include "studies/score/report.h"
#include "studies/score/spread.h"

namespace {

using namespace gyrotherm;

constexpr std::size_t kTrials = 10;

// Set up once: files loaded, settings checked, the thermal trace integrated
// (about 20 ms for the cycle, serial). What is timed below is running the
// trials, the part threads share; results/benchmarks.md also times whole
// 100-trial `gyrotherm score` commands, set-up included.
const studies::Campaign& campaign() {
  static const studies::Campaign c = [] {
    studies::ScoreOptions o;
    o.scenario = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml";
    o.trials = static_cast<int>(kTrials);
    return studies::Campaign(o);
  }();
  return c;
}

std::vector<std::size_t> all_trials() {
  std::vector<std::size_t> k(kTrials);
  std::iota(k.begin(), k.end(), std::size_t{0});
  return k;
}

double run_seconds(int threads) {
  const auto k = all_trials();
  const auto started = std::chrono::steady_clock::now();
  const auto outcomes = campaign().run(k, threads);
  benchmark::DoNotOptimize(outcomes.data());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

// A fixed amount of arithmetic split over `threads` threads; its wall time.
double loop_seconds(int threads) {
  constexpr long kWork = 40'000'000;
  const auto started = std::chrono::steady_clock::now();
  std::vector<double> sums(static_cast<std::size_t>(threads), 0.0);
  {
    std::vector<std::jthread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&sums, t, threads] {
        double s = 0.0;
        for (long i = t; i < kWork; i += threads) s += std::sqrt(static_cast<double>(i));
        sums[static_cast<std::size_t>(t)] = s;
      });
  }
  benchmark::DoNotOptimize(sums.data());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void BM_Campaign(benchmark::State& state) {
  const auto threads = static_cast<int>(state.range(0));
  const auto k = all_trials();
  for (auto _ : state) {
    const auto outcomes = campaign().run(k, threads);
    benchmark::DoNotOptimize(outcomes.data());
  }
  state.counters["trials"] = static_cast<double>(k.size());
  state.counters["engines"] = static_cast<double>(campaign().engines().size());
}

void BM_CampaignSpeedup(benchmark::State& state) {
  double one = 0.0, two = 0.0, loop_one = 0.0, loop_two = 0.0;
  for (auto _ : state) {
    one += run_seconds(1);
    two += run_seconds(2);
    loop_one += loop_seconds(1);
    loop_two += loop_seconds(2);
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["seconds_1_thread"] = one / n;
  state.counters["seconds_2_threads"] = two / n;
  state.counters["speedup"] = one / two;
  state.counters["ceiling"] = loop_one / loop_two;
}

// How campaign time grows with the number of trials (the same trial indices
// as a campaign of that size; the set-up is shared and not timed).
void BM_CampaignScaling(benchmark::State& state) {
  static const studies::Campaign large = [] {
    studies::ScoreOptions o;
    o.scenario = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml";
    o.trials = 10000;
    return studies::Campaign(o);
  }();
  std::vector<std::size_t> k(static_cast<std::size_t>(state.range(0)));
  std::iota(k.begin(), k.end(), std::size_t{0});
  double seconds = 0.0;
  for (auto _ : state) {
    const auto started = std::chrono::steady_clock::now();
    const auto outcomes = large.run(k, 2);
    benchmark::DoNotOptimize(outcomes.data());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  state.counters["trials"] = static_cast<double>(k.size());
  state.counters["ms_per_trial"] = 1e3 * seconds / static_cast<double>(state.iterations()) / static_cast<double>(k.size());
}

BENCHMARK(BM_Campaign)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CampaignScaling)->Arg(100)->Arg(1000)->Arg(10000)->Iterations(1)->Repetitions(1)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CampaignSpeedup)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
