#include "app/farm_plan.h"

#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "app/slurm_syntax.h"
#include "renderer/image.h"
#include "renderer/state_file.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// Far more than a plan of kMaxFarmJobs ids needs.
constexpr size_t kMaxPlanBytes = size_t(1) << 20;
constexpr size_t kMaxPathBytes = 4096;
constexpr int64_t kMaxSpp = int64_t(1) << 32;
constexpr long kMaxFilmSide = 16384;

// Reads the fields of one plan file, each error naming the file and the field.
class PlanReader {
 public:
  PlanReader(const fs::path& file, const nlohmann::json& j) : file_(file), j_(j) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw FarmPlanError(file_.string() + ": \"" + field + "\": " + problem);
  }

  const nlohmann::json& at(const std::string& field) const {
    if (!j_.contains(field)) fail(field, "missing");
    return j_.at(field);
  }

  int64_t integer(const std::string& field, int64_t lo, int64_t hi, const std::string& bound = "") const {
    const nlohmann::json& v = at(field);
    const std::string expects = "expects an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + bound;
    if (!v.is_number_integer()) fail(field, expects + ", got " + brief(v));
    if (v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(std::numeric_limits<int64_t>::max()))
      fail(field, expects + ", got " + v.dump());
    const int64_t n = v.get<int64_t>();
    if (n < lo || n > hi) fail(field, expects + ", got " + std::to_string(n));
    return n;
  }

  std::string text(const std::string& field, const nlohmann::json& v) const {
    if (!v.is_string()) fail(field, "expects a string, got " + brief(v));
    std::string s = v.get<std::string>();
    if (const auto problem = script_text_problem(s)) fail(field, *problem);
    if (s.size() > kMaxPathBytes) fail(field, "longer than " + std::to_string(kMaxPathBytes) + " bytes");
    return s;
  }
  std::string text(const std::string& field) const { return text(field, at(field)); }

  std::string absolute_path(const std::string& field) const {
    std::string s = text(field);
    if (s.empty() || s[0] != '/') fail(field, "expects an absolute path, got '" + s + "'");
    return s;
  }

  std::string job_id(const std::string& field, const nlohmann::json& v) const {
    std::string s = text(field, v);
    if (const auto problem = job_id_problem(s)) fail(field, *problem + ", got '" + s + "'");
    return s;
  }

  // A value for a message: its JSON, cut short.
  static std::string brief(const nlohmann::json& v) {
    std::string s = v.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
    return s.size() > 40 ? s.substr(0, 40) + "..." : s;
  }

 private:
  fs::path file_;
  const nlohmann::json& j_;
};

}  // namespace

fs::path farm_folder(const std::string& output) {
  const fs::path out = fs::absolute(output);
  return out.parent_path() / (out.stem().string() + ".farm");
}

fs::path farm_plan_file(const fs::path& folder) { return folder / "farm.json"; }

SampleRange farm_part_range(const FarmPlan& p, int i) {
  return {p.spp * i / p.parts, p.spp * (i + 1) / p.parts};
}

fs::path farm_part_file(const fs::path& folder, int i) {
  char name[32];
  std::snprintf(name, sizeof name, "part-%04d.exr", i);
  return folder / "parts" / name;
}

std::optional<std::string> script_text_problem(const std::string& text) {
  if (text.find('\n') != std::string::npos) return "holds a newline (it would end a line of a Slurm script)";
  if (text.find('\r') != std::string::npos) return "holds a carriage return (a Slurm script's lines cannot)";
  if (text.find('\0') != std::string::npos) return "holds a NUL byte";
  return std::nullopt;
}

std::optional<std::string> farm_folder_problem(const fs::path& folder) {
  if (const auto problem = script_text_problem(folder.string())) return problem;
  if (!slurm_filename_literal(folder.string()))
    return std::string("holds a backslash (Slurm's log file names cannot: one turns off %a)");
  return std::nullopt;
}

std::string farm_plan_json(const FarmPlan& p) {
  nlohmann::json j = {{"project", p.project}, {"output", p.output}, {"glint", p.glint}, {"spp", p.spp},
                      {"parts", p.parts}, {"partition", p.partition}, {"gpus_per_task", p.gpus_per_task},
                      {"job_ids", p.job_ids}, {"merge_job", p.merge_job}};
  if (p.width) j["width"] = *p.width;
  if (p.height) j["height"] = *p.height;
  return j.dump(2) + "\n";
}

std::optional<FarmPlan> read_farm_plan(const fs::path& folder) {
  const fs::path file = farm_plan_file(folder);
  const std::optional<std::string> text = read_state_file(file, kMaxPlanBytes);
  if (!text) return std::nullopt;
  nlohmann::json j;
  try {
    // A plan nests two deep (the object, job_ids): deeper input is refused while it is read.
    j = nlohmann::json::parse(*text, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (depth > 4) throw FarmPlanError("nested deeper than a plan");
      return true;
    });
  } catch (const std::exception& e) {
    throw FarmPlanError(file.string() + ": not a farm plan (" + e.what() + ")");
  }
  if (!j.is_object()) throw FarmPlanError(file.string() + ": not a farm plan (expects a JSON object)");
  const PlanReader r(file, j);
  FarmPlan p;
  p.project = r.absolute_path("project");
  p.output = r.absolute_path("output");
  if (const auto problem = output_format_problem(p.output)) r.fail("output", *problem);
  p.glint = r.absolute_path("glint");
  p.spp = r.integer("spp", 1, kMaxSpp);
  p.parts = static_cast<int>(r.integer("parts", 1, std::min<int64_t>(p.spp, kMaxFarmParts),
                                       p.spp < kMaxFarmParts ? " (at most spp)" : ""));
  for (const char* side : {"width", "height"})
    if (j.contains(side)) (side[0] == 'w' ? p.width : p.height) = static_cast<long>(r.integer(side, 1, kMaxFilmSide));
  p.partition = r.text("partition");
  if (!p.partition.empty())
    if (const auto problem = partition_problem(p.partition)) r.fail("partition", *problem);
  p.gpus_per_task = static_cast<int>(r.integer("gpus_per_task", 0, kMaxGpusPerTask));
  const nlohmann::json& ids = r.at("job_ids");
  if (!ids.is_array()) r.fail("job_ids", "expects an array of job ids, got " + PlanReader::brief(ids));
  if (ids.size() > kMaxFarmJobs)
    r.fail("job_ids", "holds " + std::to_string(ids.size()) + " job ids, more than a plan keeps (" +
                          std::to_string(kMaxFarmJobs) + ")");
  for (size_t i = 0; i < ids.size(); ++i) p.job_ids.push_back(r.job_id("job_ids[" + std::to_string(i) + "]", ids[i]));
  const nlohmann::json& merge = r.at("merge_job");
  if (!(merge.is_string() && merge.get<std::string>().empty())) p.merge_job = r.job_id("merge_job", merge);
  return p;
}

}  // namespace glint
