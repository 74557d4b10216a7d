// The output files' machinery: the number writers against fmt (whose text the files had before
// them), the writers' two ways of writing, and samples of positions only against full ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "number_text.hpp"
#include "whatnext/config.hpp"
#include "core/model.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace wn = whatnext;

namespace {

std::string f8_3(double v) {
  char out[8];
  return std::string(out, wn::numtext::put_f8_3(out, v));
}
std::string g9(double v) {
  char out[wn::numtext::kG9Room];
  return std::string(out, wn::numtext::put_g9(out, v));
}
// fmt's text, as fortran_f made it for the .dat and CsvWriter for the CSV before numtext.
std::string fmt_f8_3(double v) {
  std::string s = fmt::format("{:>8.3f}", v);
  return s.size() > 8 ? std::string(8, '*') : s;
}
std::string fmt_g9(double v) { return fmt::format("{:.9g}", v); }

// Doubles of every kind: random bit patterns, magnitudes across the files' range, decimals with
// 3 and 9 digits and their neighbours (the rounding's hard cases: near and at halves), multiples
// of the output steps.
std::vector<double> hard_doubles(std::size_t n) {
  std::mt19937_64 rng(20261123);
  std::vector<double> out;
  auto both = [&](double v) {  // the writers take finite numbers only
    for (const double w : {v, -v, std::nextafter(v, INFINITY), std::nextafter(v, -INFINITY)}) {
      if (std::isfinite(w)) out.push_back(w);
    }
  };
  while (out.size() < n) {
    const std::uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) out.push_back(v);
    both(std::ldexp(static_cast<double>(rng() >> 11) * 0x1.0p-53, static_cast<int>(rng() % 80) - 40));
    both(static_cast<double>(rng() % 20'000'000) / 2000.0);  // halves of the third decimal
    both(static_cast<double>(rng() % 2'000'000'000) / 2.0 *
         std::pow(10.0, static_cast<int>(rng() % 30) - 20));
    both(static_cast<double>(rng() % 100'000) * 0.00025);
    both(std::ldexp(static_cast<double>(rng() % 8192), -static_cast<int>(rng() % 16)));  // exact ties
  }
  for (double v : {0.0,
                   -0.0,
                   0.0625,
                   0.1875,
                   9999.999,
                   9999.9995,
                   -999.9995,
                   99999.9995,
                   1e4,
                   1e5,
                   1e9,
                   999999999.5,
                   1e-4,
                   9.99999999e-5,
                   1e-5,
                   1e22,
                   1e23,
                   5e-324,
                   2.2250738585072014e-308,
                   1.7976931348623157e308,
                   1234567.125,
                   1234567.375}) {
    both(v);
  }
  return out;
}

TEST(NumberText, SameTextAsFmtForTheDat) {
  for (const double v : hard_doubles(400'000)) ASSERT_EQ(f8_3(v), fmt_f8_3(v)) << fmt::format("{:.17g}", v);
}

TEST(NumberText, SameTextAsFmtForTheCsv) {
  for (const double v : hard_doubles(400'000)) ASSERT_EQ(g9(v), fmt_g9(v)) << fmt::format("{:.17g}", v);
}

TEST(NumberText, TheFortranLayout) {
  // Independent of fmt: Fortran's F8.3 right-justifies, rounds, and fills with asterisks.
  EXPECT_EQ(f8_3(0.0), "   0.000");
  EXPECT_EQ(f8_3(-0.3), "  -0.300");
  EXPECT_EQ(f8_3(1929.5922), "1929.592");
  EXPECT_EQ(f8_3(-999.999), "-999.999");
  EXPECT_EQ(f8_3(-1000.0), "********");
  EXPECT_EQ(f8_3(12345.6), "********");
  EXPECT_EQ(g9(0.000123456789012), "0.000123456789");
  EXPECT_EQ(g9(1.5e-7), "1.5e-07");
  EXPECT_EQ(g9(-2.0), "-2");
  EXPECT_EQ(g9(19.94410000000001), "19.9441");
}

wn::Scenario example_with(int n, const std::vector<std::string>& sets) {
  wn::Config c = wn::example_config(n);
  for (const std::string& s : sets) wn::apply_set(c, s);
  return wn::build_scenario(c);
}

template <class Writer>
std::string written(const wn::Scenario& sc, wn::Writing how) {
  std::ostringstream out;
  Writer w(out, how);
  wn::simulate(sc, &w);
  EXPECT_TRUE(out.good());
  return out.str();
}

TEST(Writers, OnTwoThreadsTheSameBytesAsOnOne) {
  // Example 3 at the paper's step: 80,000 rows, many blocks; example 1: fewer rows than a block.
  for (const wn::Scenario& sc : {example_with(3, {"run.output_step=0.00025"}), example_with(1, {})}) {
    const std::string dat = written<wn::DatWriter>(sc, wn::Writing::at_once);
    EXPECT_EQ(written<wn::DatWriter>(sc, wn::Writing::parallel), dat);
    const std::string csv = written<wn::CsvWriter>(sc, wn::Writing::at_once);
    EXPECT_EQ(written<wn::CsvWriter>(sc, wn::Writing::parallel), csv);
    EXPECT_GT(std::count(dat.begin(), dat.end(), '\n'), 400);
  }
}

TEST(Writers, AFailingStreamIsMarkedBadOnTwoThreadsToo) {
  // A stream buffer that takes 1000 bytes and then refuses: the row that does not fit fails.
  struct Full : std::streambuf {
    std::streamsize left = 1000;
    std::streamsize xsputn(const char*, std::streamsize n) override {
      const std::streamsize took = std::min(n, left);
      left -= took;
      return took;
    }
    int_type overflow(int_type) override { return traits_type::eof(); }
  };
  for (const wn::Writing how : {wn::Writing::at_once, wn::Writing::parallel}) {
    Full buf;
    std::ostream out(&buf);
    wn::DatWriter w(out, how);
    wn::simulate(example_with(3, {"run.output_step=0.00025"}), &w);
    EXPECT_TRUE(out.bad());
  }
}

TEST(Writers, ARowThatIsNotFiniteFailsTheBatchOnEitherThread) {
  // 5000 samples of the machine at rest, one of them (in a late chunk, most likely the helper's
  // on two threads) not finite: the writer throws, and nothing of that row or after it is written.
  const wn::Scenario sc = example_with(3, {});
  const wn::Model model(sc);
  std::vector<wn::Event> events;
  const wn::HybridState hs = model.initial(events);
  for (const std::size_t bad : {std::size_t{0}, std::size_t{3000}, std::size_t{4999}}) {
    for (const wn::Writing how : {wn::Writing::at_once, wn::Writing::parallel}) {
      wn::SampleBatch batch(model, false);
      batch.start(hs.d);
      for (std::size_t i = 0; i < 5000; ++i) {
        wn::State y = hs.y;
        if (i == bad) y[wn::slot::x] = std::nan("");
        batch.add(1e-3 * static_cast<double>(i), y);
      }
      std::ostringstream out;
      wn::DatWriter dat(out, how);
      EXPECT_THROW(dat.on_samples(batch), wn::SimulationError) << bad;
      const std::string text = out.str();
      EXPECT_LE(std::count(text.begin(), text.end(), '\n'), static_cast<long>(bad)) << bad;
      EXPECT_EQ(text.find("nan"), std::string::npos);
      std::ostringstream csv_out;
      wn::CsvWriter csv(csv_out, how);
      EXPECT_THROW(csv.on_samples(batch), wn::SimulationError) << bad;
    }
  }
}

// Records the times of samples and events in the order they arrive.
class Order : public wn::Observer {
 public:
  void on_samples(const wn::SampleBatch& b) override {
    ++batches;
    for (std::size_t i = 0; i < b.size(); ++i) times.push_back(b.time(i));
  }
  void on_event(const wn::Event& e) override {
    times.push_back(e.t);
    event_at.push_back(times.size() - 1);
  }
  std::vector<double> times;
  std::vector<std::size_t> event_at;
  int batches = 0;
};

TEST(Samples, BatchesArriveInTimeOrderAndNeverStraddleAnEvent) {
  // Example 3 at the paper's step: 80,000 samples in batches, and events between them.
  Order o;
  const wn::Result r = wn::simulate(example_with(3, {"run.output_step=0.00025"}), &o);
  ASSERT_EQ(o.event_at.size(), r.events.size());
  EXPECT_GT(o.batches, 19);  // 20 s at 0.25 ms is 80,001 samples: more than one batch's worth
  for (std::size_t i = 1; i < o.times.size(); ++i) ASSERT_LE(o.times[i - 1], o.times[i]) << i;
  // The grid: every sample at n * 0.00025 s up to the last event, none missing, none twice.
  std::size_t n = 0;
  for (std::size_t i = 0; i < o.times.size(); ++i) {
    if (std::find(o.event_at.begin(), o.event_at.end(), i) != o.event_at.end()) continue;
    ASSERT_NEAR(o.times[i], 0.00025 * static_cast<double>(n), 1e-12) << i;
    ++n;
  }
  EXPECT_EQ(n, static_cast<std::size_t>(std::floor(r.outcome().t / 0.00025 + 1e-9)) + 1);
}

// Keeps the samples it is given, asking for the detail it was made with.
class Samples : public wn::Observer {
 public:
  explicit Samples(Detail d) : detail_(d) {}
  Detail sample_detail() const override { return detail_; }
  void on_sample(const wn::Snapshot& s) override { got.push_back(s); }
  std::vector<wn::Snapshot> got;

 private:
  Detail detail_;
};

// Keeps only the batches' positions (SampleBatch::positions), as the .dat writer reads them.
class BatchPositions : public wn::Observer {
 public:
  Detail sample_detail() const override { return Detail::positions; }
  void on_samples(const wn::SampleBatch& batch) override {
    for (std::size_t i = 0; i < batch.size(); ++i) got.push_back(batch.positions(i));
  }
  std::vector<wn::Positions> got;
};

TEST(Samples, PositionsAreTheFullSamplesPositionsBitForBit) {
  // Every way a machine moves: the examples (example 3 spends most of its time in the lid's chart),
  // a seesaw with mass (its own swing, unloaded or carrying the sandbag), a finite arm, the radio,
  // drag, a damped hinge, a lid too heavy to lift, and the fixed-step integrators.
  const std::vector<std::vector<std::string>> variants = {
      {},
      {"seesaw.mass=0.4"},
      {"seesaw.mass=0.8", "seesaw.left_arm=0.5", "damping.pivot=0.01"},
      {"radio.enabled=true", "balloon.drag=true"},
      {"damping.lid_hinge=0.02", "run.integrator=euler", "run.step=0.001"},
      {"run.integrator=rk4", "run.step=0.001", "seesaw.mass=0.3"},
      {"masses.lid=50"},  // too heavy to lift: the sandbag slides on the arm the rope holds (M5)
  };
  std::vector<int> modes(6, 0);
  for (int ex = 1; ex <= 4; ++ex) {
    for (const auto& sets : variants) {
      wn::Scenario sc;
      try {
        sc = example_with(ex, sets);
      } catch (const wn::InputError&) {
        continue;  // a variant that does not fit this example
      }
      sc.run.output_step = std::fmin(sc.run.output_step, 0.002);
      Samples full(wn::Observer::Detail::full), positions(wn::Observer::Detail::positions);
      BatchPositions alone;
      wn::simulate(sc, &full);
      wn::simulate(sc, &positions);
      wn::simulate(sc, &alone);
      ASSERT_EQ(full.got.size(), positions.got.size());
      ASSERT_EQ(full.got.size(), alone.got.size());
      for (std::size_t i = 0; i < full.got.size(); ++i) {
        const wn::Snapshot& a = full.got[i];
        const wn::Snapshot& b = positions.got[i];
        const std::string where = fmt::format("example {} {} at t = {}", ex, fmt::join(sets, " "), a.t);
        ASSERT_EQ(a.mode, b.mode) << where;
        ASSERT_EQ(a.rope_taut, b.rope_taut) << where;
        ASSERT_EQ(a.on_seesaw, b.on_seesaw) << where;
        for (const auto& [name, x, y] : {std::tuple{"t", a.t, b.t},
                                         {"x", a.x, b.x},
                                         {"h", a.h, b.h},
                                         {"r", a.r, b.r},
                                         {"phi_s", a.phi_s, b.phi_s},
                                         {"phi_l", a.phi_l, b.phi_l},
                                         {"balloon_h", a.balloon_h, b.balloon_h},
                                         {"balloon_limit", a.balloon_limit, b.balloon_limit}}) {
          ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << where << ": " << name << " " << x << " vs " << y;
        }
        EXPECT_EQ(b.tension, 0.0) << where;  // positions only: no contact problem solved
        const wn::Positions& c = alone.got[i];
        ASSERT_EQ(a.mode, c.mode) << where;
        ASSERT_EQ(a.rope_taut, c.rope_taut) << where;
        for (const auto& [name, x, y] : {std::tuple{"t", a.t, c.t},
                                         {"x", a.x, c.x},
                                         {"h", a.h, c.h},
                                         {"phi_s", a.phi_s, c.phi_s},
                                         {"phi_l", a.phi_l, c.phi_l},
                                         {"balloon_h", a.balloon_h, c.balloon_h},
                                         {"balloon_limit", a.balloon_limit, c.balloon_limit}}) {
          ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0)
              << where << ": Positions' " << name << " " << x << " vs " << y;
        }
        ++modes[static_cast<int>(a.mode)];
      }
    }
  }
  for (int m = 1; m <= 5; ++m) EXPECT_GT(modes[m], 0) << "no sample in mode M" << m;
}

}  // namespace
