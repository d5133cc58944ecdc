#include "core/commands/volume_render.h"

#include <algorithm>
#include <cmath>

namespace trispline::core {
namespace {

using RenderField = ParamSchema<VolumeRenderParams>::Field;

void read_transfer(const RenderField&, const nlohmann::json& v, VolumeRenderParams& p, const CommandContext&) {
  if (!v.is_array()) params::fail("transfer", "expected a list of [value, r, g, b, a] points");
  if (v.size() > std::size_t(kMaxTransferPoints))
    params::fail("transfer",
                 "at most " + std::to_string(kMaxTransferPoints) + " points, got " + std::to_string(v.size()));
  TransferFunction tf;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const nlohmann::json& e = v[i];
    if (!e.is_array() || e.size() != 5 || !std::all_of(e.begin(), e.end(), [](const auto& x) { return x.is_number(); }))
      params::fail("transfer", "point " + std::to_string(i) + ": expected [value, r, g, b, a] (five numbers)");
    tf.points.push_back(
        {e[0].get<double>(), {e[1].get<double>(), e[2].get<double>(), e[3].get<double>(), e[4].get<double>()}});
  }
  if (const std::string why = transfer_function_error(tf); !why.empty()) params::fail("transfer", why);
  p.transfer = std::move(tf);
}

void write_transfer(const RenderField&, const VolumeRenderParams& p, nlohmann::json& line) {
  if (!p.transfer) return;
  nlohmann::json out = nlohmann::json::array();
  for (const TransferPoint& t : p.transfer->points) out.push_back({t.value, t.rgba.x, t.rgba.y, t.rgba.z, t.rgba.w});
  line["transfer"] = std::move(out);
}

}  // namespace

TransferFunction default_transfer_function(const VolumeObject& volume) {
  if (volume.units == "HU") return ct_transfer_function();
  const std::vector<float>& c = volume.spline->control_points();
  const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
  double a = std::clamp(volume.iso, double(*lo), double(*hi)), b = *hi;
  if (!(b > a)) a = *lo, b = *hi;
  if (!(b > a)) b = a + 1.0;
  return {{{a, {0.90, 0.60, 0.45, 0.0}}, {a + 0.25 * (b - a), {0.95, 0.80, 0.60, 0.05}}, {b, {1.0, 1.0, 1.0, 0.6}}}};
}

auto VolumeRenderCommand::declare() -> Schema {
  return Schema("volume.render",
                "Draw a volume as its iso-surface or by direct volume rendering through a transfer function "
                "(seed §7.4, Fig. 7.7)")
      .field("object", &P::object, {.required = true, .help = "A volume"})
      .choice("mode", &P::mode, {"iso", "dvr"},
              {.ui = {"Render"},
               .help = "iso: the iso-surface D = iso-level, ray cast on the spline; dvr: emission and absorption "
                       "along each ray through the transfer function"})
      .custom("transfer", read_transfer, write_transfer,
              {.default_text = "kept",
               .type_text = "[[value,r,g,b,a],…]",
               .help = "dvr's transfer function: 2 to 16 points, values in the volume's units increasing, linear "
                       "RGB and opacity per index unit in [0,1], linear between points"})
      .field("step", &P::step,
             {.write = ParamWrite::UnlessDefault,
              .range = ParamRange{1.0 / 64.0, 4.0},
              .unit = "index units",
              .ui = {"Step", 0.01, "%.3f"},
              .help = "dvr's segment length along a ray; smaller is finer and slower"})
      .label([](const P& p) {
        return p.mode == VolumeObject::RenderMode::dvr ? "Direct volume rendering of '" + p.object + "'"
                                                       : "Iso-surface of '" + p.object + "'";
      });
}

std::optional<VolumeObject> VolumeRenderCommand::build(const Scene& scene) {
  VolumeObject v = require_volume(scene, p_.object);
  v.render_mode = p_.mode;
  if (p_.transfer) v.transfer = *p_.transfer;
  if (v.render_mode == VolumeObject::RenderMode::dvr && v.transfer.points.empty())
    v.transfer = default_transfer_function(v);
  v.dvr_step = p_.step;
  stats_["mode"] = p_.mode == VolumeObject::RenderMode::dvr ? "dvr" : "iso";
  stats_["points"] = v.transfer.points.size();
  stats_["step"] = v.dvr_step;
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const TransferPoint& t : v.transfer.points)
    if (t.rgba.w > 0.0) {
      lo = any ? std::min(lo, t.value) : t.value, hi = any ? std::max(hi, t.value) : t.value;
      any = true;
    }
  if (any) stats_["visible_range"] = {lo, hi};
  return v;
}

}  // namespace trispline::core
