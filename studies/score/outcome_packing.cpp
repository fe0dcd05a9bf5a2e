#include "studies/score/outcome_packing.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace gyrotherm::studies {

namespace {

class Writer {
 public:
  template <class T>
  void put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_.append(bytes, sizeof(T));
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    out_ += s;
  }
  void put_doubles(const std::vector<double>& v) {
    put<std::uint64_t>(v.size());
    for (double x : v) put(x);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string get_string() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    need(n);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  std::vector<double> get_doubles() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    need(n * sizeof(double));
    std::vector<double> v(n);
    for (double& x : v) x = get<double>();
    return v;
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw std::runtime_error("score: truncated trial outcomes");
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::string pack_outcomes(std::span<const TrialOutcome> outcomes) {
  Writer w;
  w.put<std::uint64_t>(outcomes.size());
  for (const TrialOutcome& o : outcomes) {
    w.put<std::uint64_t>(o.index);
    w.put<std::uint64_t>(o.seed);
    w.put_string(o.error);
    w.put(o.before_dph);
    w.put(o.optimum_dph);
    w.put<std::uint64_t>(o.engines.size());
    for (const EngineTrial& e : o.engines) {
      w.put<std::uint8_t>(e.reached ? 1 : 0);
      w.put<std::int64_t>(e.evaluations);
      w.put<std::int64_t>(e.evaluations_to_target);
      w.put(e.seconds);
      w.put(e.gap);
      w.put(e.ratio);
      w.put<std::int32_t>(static_cast<std::int32_t>(e.termination));
      w.put_doubles(e.coefficient_error);
      w.put_doubles(e.curve_gap);
    }
  }
  return w.take();
}

std::vector<TrialOutcome> unpack_outcomes(std::string_view bytes) {
  Reader r(bytes);
  std::vector<TrialOutcome> out(static_cast<std::size_t>(r.get<std::uint64_t>()));
  for (TrialOutcome& o : out) {
    o.index = static_cast<std::size_t>(r.get<std::uint64_t>());
    o.seed = r.get<std::uint64_t>();
    o.error = r.get_string();
    o.before_dph = r.get<double>();
    o.optimum_dph = r.get<double>();
    o.engines.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
    for (EngineTrial& e : o.engines) {
      e.reached = r.get<std::uint8_t>() != 0;
      e.evaluations = static_cast<long>(r.get<std::int64_t>());
      e.evaluations_to_target = static_cast<long>(r.get<std::int64_t>());
      e.seconds = r.get<double>();
      e.gap = r.get<double>();
      e.ratio = r.get<double>();
      e.termination = static_cast<fit::Termination>(r.get<std::int32_t>());
      e.coefficient_error = r.get_doubles();
      e.curve_gap = r.get_doubles();
    }
  }
  if (!r.at_end()) throw std::runtime_error("score: trailing bytes after the trial outcomes");
  return out;
}

}  // namespace gyrotherm::studies
