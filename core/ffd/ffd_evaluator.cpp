// FfdEvaluator contract: backend names, the CPU factory and the cpu_ref backend (double reference, ffd.h).
// The cpu_fast backend lives in ffd_fast.cpp (FfdFastEvaluator) and its kernels in ffd_fast_kernel_*.cpp.
#include "core/ffd/ffd_evaluator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/base/enum_names.h"
#include "core/ffd/ffd_fast.h"

namespace trispline::core {

const char* to_string(FfdBackend backend) {
  return enum_name(backend, {"cpu_ref", "cpu_fast", "glsl_compute", "glsl_vertex"}, "unknown");
}

std::optional<FfdBackend> parse_ffd_backend(std::string_view name) {
  for (FfdBackend b : {FfdBackend::cpu_ref, FfdBackend::cpu_fast, FfdBackend::glsl_compute, FfdBackend::glsl_vertex})
    if (name == to_string(b)) return b;
  return std::nullopt;
}

namespace detail {

void check_ffd_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals,
                        const char* who) {
  if (!rest_normals.empty() && rest_normals.size() != params.size())
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(rest_normals.size()) + " rest normals for " +
                                std::to_string(params.size()) + " parameters (need none or one per vertex)");
  auto finite = [](const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
  for (std::size_t i = 0; i < params.size(); ++i)
    if (!finite(params[i]))
      throw std::invalid_argument(std::string(who) + ": parameter " + std::to_string(i) + " is not finite");
  for (std::size_t i = 0; i < rest_normals.size(); ++i)
    if (!finite(rest_normals[i]))
      throw std::invalid_argument(std::string(who) + ": rest normal " + std::to_string(i) + " is not finite");
}

}  // namespace detail

namespace {

// cpu_ref: the double reference (ffd_evaluate), parameters shifted by param_offset before evaluation.
class CpuRefEvaluator final : public FfdEvaluator {
 public:
  FfdBackend backend() const override { return FfdBackend::cpu_ref; }

  void bind_vertices(const std::vector<glm::dvec3>& params, const std::vector<glm::dvec3>& rest_normals) override {
    detail::check_ffd_vertices(params, rest_normals, "cpu_ref bind_vertices");
    params_ = params;
    normals_ = rest_normals;
    bound_ = true;
    evaluated_ = false;
  }

  void set_lattice(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding) override {
    lattice_.emplace(lattice);
    embedding_ = embedding;
  }

  void evaluate(const glm::dvec3& param_offset) override {
    if (!bound_ || !lattice_)
      throw std::logic_error("cpu_ref evaluate: bind_vertices and set_lattice must be called first");
    const std::vector<glm::dvec3>* p = &params_;
    if (param_offset != glm::dvec3(0.0)) {
      shifted_.resize(params_.size());
      for (std::size_t i = 0; i < params_.size(); ++i) shifted_[i] = params_[i] + param_offset;
      p = &shifted_;
    }
    if (normals_.empty()) {
      ffd_evaluate(*lattice_, *p, positions_);
      out_normals_.clear();
    } else {
      ffd_evaluate(*lattice_, embedding_, *p, normals_, positions_, out_normals_);
    }
    evaluated_ = true;
  }

  void read_results(std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) override {
    if (!evaluated_) throw std::logic_error("cpu_ref read_results: evaluate() has not run since bind_vertices");
    positions = positions_;
    normals = out_normals_;
  }

  std::size_t vertex_count() const override { return params_.size(); }
  bool has_normals() const override { return !normals_.empty(); }

 private:
  std::vector<glm::dvec3> params_, normals_, shifted_, positions_, out_normals_;
  std::optional<TrivariateBSpline<glm::dvec3>> lattice_;
  Embedding embedding_;
  bool bound_ = false, evaluated_ = false;
};

}  // namespace

std::unique_ptr<FfdEvaluator> make_cpu_ffd_evaluator(FfdBackend backend) {
  switch (backend) {
    case FfdBackend::cpu_ref:
      return std::make_unique<CpuRefEvaluator>();
    case FfdBackend::cpu_fast:
      return std::make_unique<FfdFastEvaluator>();
    default:
      throw std::invalid_argument(std::string("make_cpu_ffd_evaluator: ") + to_string(backend) +
                                  " is a GPU backend (made by gpu::make_gl_ffd_evaluator with a GL context)");
  }
}

void FfdEvaluator::read_results_float(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  std::vector<glm::dvec3> p, n;
  read_results(p, n);
  positions.assign(p.begin(), p.end());
  normals.assign(n.begin(), n.end());
}

void FfdEvaluator::read_results_into(double* positions, double* normals) {
  std::vector<glm::dvec3> p, n;
  read_results(p, n);
  std::copy_n(&p[0].x, 3 * p.size(), positions);
  if (normals && !n.empty()) std::copy_n(&n[0].x, 3 * n.size(), normals);
}

void FfdEvaluator::evaluate_into(const glm::dvec3& param_offset, double* positions, double* normals) {
  evaluate(param_offset);
  read_results_into(positions, normals);
}

}  // namespace trispline::core
