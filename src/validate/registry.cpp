#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

// Defined in the case files.
CaseInfo slitFraunhoferCase();
CaseInfo doubleSlitCase();
CaseInfo rectApertureCase();
CaseInfo slitFresnelCase();
CaseInfo doorRsCase();
CaseInfo gratingOrdersCase();
CaseInfo freeFieldCase();
CaseInfo shoeboxIsmCase();
CaseInfo specularDecayCase();
CaseInfo diffuseEyringCase();
CaseInfo decayMetricsCase();
CaseInfo halfPlaneCase();
CaseInfo barrierCase();
CaseInfo doorRoomCase();
CaseInfo imageDoubleSlitCase();
CaseInfo imageCdCase();
CaseInfo imageLensPsfCase();
CaseInfo twoRoomsWaveCase();
CaseInfo classroomWaveCase();

const std::vector<CaseInfo>& cases() {
  static const std::vector<CaseInfo> all{slitFraunhoferCase(), doubleSlitCase(), rectApertureCase(),
                                         slitFresnelCase(),    doorRsCase(),     gratingOrdersCase(),
                                         freeFieldCase(),      shoeboxIsmCase(), specularDecayCase(),
                                         diffuseEyringCase(),  decayMetricsCase(), halfPlaneCase(), barrierCase(), doorRoomCase(),
                                         imageDoubleSlitCase(), imageCdCase(),
                                         imageLensPsfCase(), twoRoomsWaveCase(), classroomWaveCase()};
  return all;
}

const ParamSpec& CaseInfo::param(const std::string& param_name) const {
  for (const ParamSpec& p : params)
    if (p.name == param_name) return p;
  throw core::InternalError("case " + name + " has no parameter " + param_name);
}
ParamSpec& CaseInfo::param(const std::string& param_name) {
  return const_cast<ParamSpec&>(static_cast<const CaseInfo&>(*this).param(param_name));
}

const CaseInfo* findCase(const std::string& name) {
  for (const auto& c : cases())
    if (c.name == name) return &c;
  return nullptr;
}

Params resolveParams(const CaseInfo& info, const Params& given) {
  Params out;
  for (const auto& p : info.params) out[p.name] = p.defaults;
  for (const auto& [name, values] : given) {
    auto it = out.find(name);
    if (it == out.end()) {
      std::string takes;
      for (const auto& p : info.params) takes += (takes.empty() ? "--" : ", --") + p.name;
      throw core::InputError("--" + name, "does not apply to case " + info.name + " (it takes " + takes + ")");
    }
    if (values.empty()) throw core::InputError("--" + name, "needs a value");
    const ParamSpec& spec = info.param(name);
    if (!spec.list && values.size() != 1)  // the case would read the first and drop the rest
      throw core::InputError("--" + name, "takes one value, got " + std::to_string(values.size()));
    for (double v : values) {
      core::requireFinite("--" + name, v);
      if (spec.whole && std::floor(v) != v) {
        char digits[32];  // the shortest text that reads back as v: 2.0000001 must not print as 2
        const std::to_chars_result end = std::to_chars(digits, digits + sizeof digits, v);
        throw core::InputError("--" + name, "must be a whole number, got " + std::string(digits, end.ptr));
      }
      const bool above = spec.min_inclusive ? v >= spec.min : v > spec.min;
      if (!above || !(v < spec.max)) {
        std::ostringstream msg;
        msg << "must be " << (spec.min_inclusive ? ">= " : "> ") << spec.min;
        msg << " and < " << spec.max;
        msg << ", got " << v;
        throw core::InputError("--" + name, msg.str());
      }
    }
    it->second = values;
  }
  return out;
}

void scoreRows(CaseResult& r) {
  // Rows with the same label form one pattern (one frequency of a sweep); errors are relative to that
  // pattern's peak, and the case's figures are the worst over its patterns.
  std::map<std::string, double> peak;
  for (const Row& row : r.rows) peak[row.label] = std::max(peak[row.label], std::abs(row.reference));
  std::map<std::string, double> max_err, sum_sq, count;
  r.max_std_error_rel_peak = 0.0;
  for (const Row& row : r.rows) {
    const double pk = peak[row.label] > 0 ? peak[row.label] : 1.0;
    const double e = std::abs(row.traced - row.reference) / pk;
    max_err[row.label] = std::max(max_err[row.label], e);
    sum_sq[row.label] += e * e;
    count[row.label] += 1.0;
    r.max_std_error_rel_peak = std::max(r.max_std_error_rel_peak, row.std_error / pk);
  }
  r.max_abs_error_rel_peak = 0.0;
  r.rms_error_rel_peak = 0.0;
  for (const auto& [label, e] : max_err) {
    const double rms = std::sqrt(sum_sq[label] / count[label]);
    r.max_abs_error_rel_peak = std::max(r.max_abs_error_rel_peak, e);
    r.rms_error_rel_peak = std::max(r.rms_error_rel_peak, rms);
    if (max_err.size() > 1) {
      r.extra["max_abs_error_rel_peak[" + label + "]"] = e;
      r.extra["rms_error_rel_peak[" + label + "]"] = rms;
    }
  }
  // A pattern whose reference is zero everywhere measures nothing (a slit far below the wavelength: both
  // patterns underflow to 0): the case cannot pass on it.
  int unmeasured = 0;
  for (const auto& [label, pk] : peak) unmeasured += !(pk > 0.0 && std::isfinite(pk));
  if (unmeasured > 0) r.extra["patterns_with_zero_reference"] = unmeasured;
  r.passed = unmeasured == 0 && !peak.empty() && r.max_abs_error_rel_peak <= r.target_rel_peak;
}

}  // namespace diffray::validate
