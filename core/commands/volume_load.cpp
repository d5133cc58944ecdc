#include "core/commands/volume_load.h"

#include <cmath>

#include "core/volume/prepared_volume.h"

namespace trispline::core {

auto VolumeLoadCommand::declare() -> Schema {
  return Schema("volume.load",
                "Load a CT/MRI volume (NIfTI, DICOM series, InVesalius .inv3) as a trivariate "
                "B-spline (seed ch. 7)")
      .field("path", &P::path,
             {.write = ParamWrite::UnlessDefault,
              .path = true,
              .help = "NIfTI (.nii, .nii.gz), a DICOM series folder or .dcm file, or an InVesalius .inv3 project; "
                      "relative to the log's folder"})
      .choice("analytic", &P::analytic, {"", "sphere", "torus", "sines"},
              {.write = ParamWrite::UnlessDefault,
               .help = "Instead of a file: an analytic test volume (96 samples a side; known silhouettes)"})
      .field("name", &P::name,
             {.write = ParamWrite::UnlessDefault, .help = "Object id (default: the file name, made unique)"})
      .field("order", &P::order,
             {.range = ParamRange{2, 4}, .help = "Spline order per axis (degree + 1): 2 linear, 3 quadratic, 4 cubic"})
      .field("interpolate", &P::interpolate,
             {.write = ParamWrite::UnlessDefault,
              .help = "false: the samples are the control points (the seed; smooths noise); true: D passes through "
                      "every sample (B-spline prefilter)"})
      .choice("axes", &P::axes, {"superior_up", "file"},
              {.help = "superior_up: the world is turned so that the patient's superior axis is +Y (anterior +Z, "
                       "right −X) in this Y-up editor, for files that name their patient frame (NIfTI RAS, DICOM "
                       "LPS); file: the file's own axes"})
      .field("iso", &P::iso,
             {.unit = "volume units",
              .help = "First iso-level (default: 226 HU for CT, else Otsu's threshold of the samples)"})
      .check([](const P& p) {
        if (p.path.empty() == p.analytic.empty())
          params::fail("path", "give either a volume file ('path') or an analytic volume ('analytic')");
      })
      .label([](const P& p) { return "Load volume '" + p.name + "'"; })
      .failure_field("path");
}

namespace {

// A 4 × 4 affine as four rows (the report's form of a transform).
nlohmann::json index_to_world_rows(const glm::dmat4& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
  return rows;
}

}  // namespace

std::optional<VolumeObject> VolumeLoadCommand::build(const Scene& scene) {
  const std::string source = p_.analytic.empty() ? p_.path : "analytic:" + p_.analytic;
  PreparedVolume pv;
  try {
    pv = prepare_volume(source, p_.order, p_.interpolate, {}, p_.axes == "superior_up");
  } catch (const PreparationBudgetError& e) {  // the dimensions leave no room for the spline and its table
    throw CommandError(std::string("field 'path': ") + e.what(), "path");
  } catch (const VolumeLoadError& e) {  // missing, truncated, over the budget from the header, ...
    throw CommandError(std::string("field 'path': ") + e.what(), "path");
  }
  if (p_.name.empty()) {
    std::filesystem::path stem =
        p_.analytic.empty() ? std::filesystem::path(p_.path).filename() : std::filesystem::path(p_.analytic);
    while (stem.has_extension()) stem = stem.stem();  // Cranium.inv3 → Cranium, brain.nii.gz → brain
    p_.name = scene.unique_name(sanitized_object_name(stem.string()));
  }
  if (const std::string bad = object_name_error(p_.name); !bad.empty())
    throw CommandError("field 'name': " + bad, "name");
  if (scene.index_of(p_.name) >= 0 || scene.volume_index_of(p_.name) >= 0)
    throw CommandError("field 'name': an object named '" + p_.name + "' already exists", "name");
  VolumeObject v;
  v.name = p_.name;
  v.source = source;
  v.units = pv.units;
  v.modality = pv.modality;
  v.spline = pv.spline;
  v.table = pv.table;
  v.iso = p_.iso.value_or(pv.default_iso);
  if (!std::isfinite(v.iso)) throw CommandError("field 'iso': must be a finite number", "iso");
  p_.iso = v.iso;  // the log line keeps the level used
  const auto& d = pv.spline->dims();
  stats_ = {{"dims", {d[0], d[1], d[2]}},
            {"order", p_.order},
            {"units", pv.units},
            {"frame", pv.frame},
            {"index_to_world", index_to_world_rows(pv.spline->index_to_world())},
            {"axes", pv.superior_up ? "superior_up" : "file"},
            {"iso", v.iso},
            {"value_range", {pv.table->range_min(), pv.table->range_max()}},
            {"load_ms", pv.load_ms},
            {"prep_ms", pv.prep_ms},
            {"table_mb", pv.table->memory_bytes() / 1048576.0}};
  return v;
}

}  // namespace trispline::core
