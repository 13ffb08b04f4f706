// Orders and the trial plan of an experiment.
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <utility>

#include "app/experiment/experiment.hpp"

#include "sim/scene/settings.hpp"
#include "app/experiment/random.hpp"

namespace gf::app {
namespace {

// Every combination of the levels of `factors` (indices into e.factors), the first varying slowest.
std::vector<std::vector<int>> crossLevels(const ExperimentDesc& e, const std::vector<int>& factors) {
  std::vector<std::vector<int>> out(1);
  for (const int f : factors) {
    std::vector<std::vector<int>> next;
    for (const std::vector<int>& combo : out) {
      for (int l = 0; l < static_cast<int>(e.factors[static_cast<std::size_t>(f)].levels.size()); ++l) {
        next.push_back(combo);
        next.back().push_back(l);
      }
    }
    out = std::move(next);
  }
  return out;
}

}  // namespace

std::vector<int> levelOrder(OrderKind kind, int n, int p) {
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  if (kind == OrderKind::kFixed || n <= 1) return order;
  if (kind == OrderKind::kLatin) {
    for (int j = 0; j < n; ++j) order[static_cast<std::size_t>(j)] = (p + j) % n;
    return order;
  }
  // Williams: the first row 0, 1, n-1, 2, n-2, ...; row r adds r (mod n). With an odd n every
  // row's reverse is used too (2n rows), so each level follows each other equally often.
  std::vector<int> first;
  for (int j = 0, lo = 1, hi = n - 1; j < n; ++j) {
    if (j == 0) first.push_back(0);
    else if (j % 2 == 1) first.push_back(lo++);
    else first.push_back(hi--);
  }
  const int rows = n % 2 == 0 ? n : 2 * n;
  const int row = p % rows;
  for (int j = 0; j < n; ++j) order[static_cast<std::size_t>(j)] = (first[static_cast<std::size_t>(j)] + row) % n;
  if (row >= n) std::reverse(order.begin(), order.end());
  return order;
}

std::string participantId(int participant) {
  char b[16];
  std::snprintf(b, sizeof b, "sub-%02d", participant + 1);
  return b;
}

std::vector<Trial> planTrials(const ExperimentDesc& e) {
  std::vector<int> between, within_others;
  int block_factor = -1;
  for (int f = 0; f < static_cast<int>(e.factors.size()); ++f) {
    const ExperimentFactor& factor = e.factors[static_cast<std::size_t>(f)];
    if (!factor.within) between.push_back(f);
    else if (factor.name == e.block_by) block_factor = f;
    else within_others.push_back(f);
  }
  const std::vector<std::vector<int>> others = crossLevels(e, within_others);
  int groups = 1;
  for (const int f : between) groups *= static_cast<int>(e.factors[static_cast<std::size_t>(f)].levels.size());
  std::vector<Trial> trials;
  for (int p = 0; p < e.participants; ++p) {
    Trial base;
    base.participant = p;
    base.levels.assign(e.factors.size(), 0);
    // Between factors: participant numbers counted in mixed radix, the first factor fastest.
    for (int rest = p; const int f : between) {
      const int n = static_cast<int>(e.factors[static_cast<std::size_t>(f)].levels.size());
      base.levels[static_cast<std::size_t>(f)] = rest % n;
      rest /= n;
    }
    const int blocks = block_factor < 0 ? 1 : static_cast<int>(e.factors[static_cast<std::size_t>(block_factor)].levels.size());
    // The participants of one between group take the square's rows in turn: each group is
    // counterbalanced on its own (the row is not the number that chose the group).
    const std::vector<int> order = levelOrder(e.order, blocks, p / groups);
    int number = 0;
    for (int b = 0; b < blocks; ++b) {
      Trial block = base;
      block.block = b + 1;
      if (block_factor >= 0) block.levels[static_cast<std::size_t>(block_factor)] = order[static_cast<std::size_t>(b)];
      std::vector<Trial> items;
      for (int task = 0; task < static_cast<int>(e.tasks.size()); ++task) {
        for (const std::vector<int>& combo : others) {
          for (int rep = 0; rep < e.repetitions; ++rep) {
            Trial t = block;
            t.task = task;
            for (std::size_t k = 0; k < within_others.size(); ++k) t.levels[static_cast<std::size_t>(within_others[k])] = combo[k];
            items.push_back(t);
          }
        }
      }
      if (e.shuffle) {
        SeededRandom rng = SeededRandom::of({e.seed, 1, static_cast<std::uint64_t>(p), static_cast<std::uint64_t>(b)});
        for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[rng.below(i)]);
      }
      std::vector<Trial> run;
      for (int k = 0; k < e.practice; ++k) {
        run.push_back(items[static_cast<std::size_t>(k) % items.size()]);
        run.back().practice = true;
      }
      run.insert(run.end(), items.begin(), items.end());
      for (Trial& t : run) {
        t.number = ++number;
        t.seed = SeededRandom::of({e.seed, 2, static_cast<std::uint64_t>(p), static_cast<std::uint64_t>(t.number)}).next();
        trials.push_back(t);
      }
    }
  }
  return trials;
}

double trialNoise(const ExperimentDesc& e, const Trial& t) {
  double noise = e.noise;
  for (std::size_t f = 0; f < e.factors.size(); ++f) {
    if (const auto& n = e.factors[f].levels[static_cast<std::size_t>(t.levels[f])].noise) noise = *n;
  }
  return noise;
}

std::size_t trialCount(const ExperimentDesc& e) {
  std::size_t per_block = e.tasks.size() * static_cast<std::size_t>(e.repetitions);
  std::size_t blocks = 1;
  for (const ExperimentFactor& f : e.factors) {
    if (!f.within) continue;
    (f.name == e.block_by ? blocks : per_block) *= f.levels.size();
  }
  return static_cast<std::size_t>(e.participants) * blocks * (per_block + static_cast<std::size_t>(e.practice));
}

std::string exactArray(std::initializer_list<double> values) {
  std::string out = "[";
  for (const double v : values) out.append(out.size() > 1 ? ", " : "").append(sim::numberText(v, 17));
  return out + "]";
}

std::string participantDeviceOverride(const ExperimentDesc& e, const sim::FingerDesc& finger, int channel) {
  const sim::Vec3 p = finger.device.keyframes.empty() ? sim::Vec3::Zero() : finger.device.keyframes.front().position;
  const std::string start = "start=" + exactArray({p.x(), p.y(), p.z()});
  std::string quoted;  // a TOML basic string
  for (const char c : e.udp) quoted += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  const std::string device = e.device == "udp" ? "udp=\"" + quoted + "\", channel=" + std::to_string(channel) : std::string("web=true");
  return "fingers." + finger.name + ".device={" + device + ", " + start + "}";
}

std::vector<std::string> trialOverrides(const ExperimentDesc& e, const Trial& t, const std::vector<std::string>& fingers) {
  std::vector<std::string> out;
  for (std::size_t f = 0; f < e.factors.size(); ++f) {
    for (const StudyOverride& o : e.factors[f].levels[static_cast<std::size_t>(t.levels[f])].set) {
      for (std::string& text : expandFingers(o.text, fingers)) out.push_back(std::move(text));
    }
  }
  return out;
}

}  // namespace gf::app
