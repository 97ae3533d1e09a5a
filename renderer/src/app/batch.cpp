#include "penumbra/batch.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "image/image_internal.h"
#include "penumbra/scene_file.h"
#include "penumbra/settings.h"

namespace penumbra {
namespace {

using nlohmann::json;

std::string lineError(int line, const std::string& message) {
  return "line " + std::to_string(line) + ": " + message;
}

// A JSON scalar as the command line would have given it.
Result<std::string> optionText(const std::string& key, const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return std::string(value.get<bool>() ? "true" : "false");
  if (value.is_number_integer()) return value.dump();
  if (value.is_number()) {
    const double v = value.get<double>();
    if (!std::isfinite(v)) return makeError("'" + key + "' is not a finite number");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return std::string(buf);
  }
  return makeError("'" + key + "' must be a string, a number or a boolean");
}

// A setting by its flag without the dashes or by its schema key, as a (key, text) override.
Result<std::pair<std::string, std::string>> settingOverride(const std::string& name,
                                                            const json& value) {
  for (const SettingInfo& info : settingsSchema()) {
    const std::string flag(info.flag);
    const bool byFlag = !flag.empty() && flag.substr(2) == name;
    if (!byFlag && info.key != name) continue;
    auto text = optionText(name, value);
    if (!text) return text.error();
    // "no-gi": true turns the setting off, as the --no-gi switch does.
    if (byFlag && info.type == SettingType::Bool && flag.rfind("--no-", 0) == 0) {
      if (!value.is_boolean()) return makeError("'" + name + "' must be true or false");
      *text = value.get<bool>() ? "false" : "true";
    }
    return std::make_pair(std::string(info.key), *text);
  }
  if (name == "gl" || name == "half-float" || name == "batch" || name == "results" ||
      name == "shard" || name == "force" || name == "quiet" || name == "info") {
    return makeError("'" + name + "' applies to the whole batch: give it on the command line");
  }
  return makeError("unknown option '" + name + "'");
}

Status applyOption(BatchJob& job, const std::string& key, const json& value) {
  if (key == "size" && value.is_array()) {
    if (value.size() != 2 || !value[0].is_number_integer() || !value[1].is_number_integer()) {
      return makeError("'size' must be \"WxH\" or [W, H]");
    }
    job.request.settings.emplace_back("width", value[0].dump());
    job.request.settings.emplace_back("height", value[1].dump());
    return {};
  }
  auto text = optionText(key, value);
  if (!text) return text.error();
  if (key == "scene") {
    job.request.scenePath = *text;
  } else if (key == "output") {
    job.output = *text;
  } else if (key == "camera") {
    job.request.camera = *text;
  } else if (key == "variant") {
    job.request.variant = *text;
  } else if (key == "animation") {
    job.request.animation = *text;
  } else if (key == "time") {
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      return makeError("'time' must be a number of seconds");
    }
    job.request.time = value.get<float>();
  } else if (key == "env") {
    auto spec = parseEnvironmentSpec(*text);
    if (!spec) return spec.error();
    job.request.environment = *spec;
  } else if (key == "size") {
    auto size = parseSize(*text);
    if (!size) return size.error();
    job.request.settings.emplace_back("width", std::to_string(size->first));
    job.request.settings.emplace_back("height", std::to_string(size->second));
  } else if (key == "memory-budget") {
    if (!value.is_number_integer() || value.get<int64_t>() < 1 ||
        value.get<int64_t>() > (int64_t{1} << 30)) {
      return makeError("'memory-budget' must be a positive number of MB");
    }
    job.request.memoryBudgetBytes = value.get<int64_t>() << 20;
  } else {
    auto setting = settingOverride(key, value);
    if (!setting) return setting.error();
    job.request.settings.push_back(*setting);
  }
  return {};
}

}  // namespace

Result<std::vector<std::string>> expandSequence(std::string_view text, int line) {
  json j = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || (!j.contains("times") && !j.contains("fps") && !j.contains("count"))) {
    return std::vector<std::string>{
        std::string(text)};  // not a sequence (or parseBatchJob's error)
  }
  std::vector<double> times;
  if (auto t = j.find("times"); t != j.end()) {
    if (!t->is_array() || t->empty() || t->size() > 100000 || j.contains("fps")) {
      return makeError(
          lineError(line, "'times' must be a non-empty list of seconds (without 'fps')"));
    }
    for (const json& v : *t) {
      if (!v.is_number() || !std::isfinite(v.get<double>())) {
        return makeError(lineError(line, "'times' must hold numbers of seconds"));
      }
      times.push_back(v.get<double>());
    }
  } else {
    const json fps = j.value("fps", json()), count = j.value("count", json());
    const json start = j.value("start", json(0.0));
    if (!fps.is_number() || !(fps.get<double>() > 0.0) || !std::isfinite(fps.get<double>()) ||
        !count.is_number_integer() || count.get<int64_t>() < 1 || count.get<int64_t>() > 100000 ||
        !start.is_number() || !std::isfinite(start.get<double>())) {
      return makeError(lineError(line,
                                 "a sequence needs 'fps' > 0 and 'count' (1 to 100000), "
                                 "and a finite 'start'"));
    }
    for (int64_t i = 0; i < count.get<int64_t>(); ++i) {
      times.push_back(start.get<double>() + static_cast<double>(i) / fps.get<double>());
    }
  }
  if (j.contains("time")) {
    return makeError(lineError(line, "a sequence takes 'times' or 'fps' and 'count', not 'time'"));
  }
  const std::string output = j.value("output", std::string());
  for (const char* key : {"times", "fps", "count", "start"}) j.erase(key);
  std::vector<std::string> lines;
  for (size_t i = 0; i < times.size(); ++i) {
    char number[24];
    std::snprintf(number, sizeof number, "%04zu", i);
    std::string out = output;
    if (const size_t hashes = out.find("####"); hashes != std::string::npos) {
      out.replace(hashes, 4, number);
    } else {
      const size_t dot = out.find_last_of('.');
      const size_t slash = out.find_last_of("/\\");
      const size_t at = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                            ? out.size()
                            : dot;
      out.insert(at, std::string("_") + number);
    }
    json one = j;
    one["time"] = times[i];
    if (!output.empty()) one["output"] = out;
    lines.push_back(one.dump());
  }
  return lines;
}

bool isImageOutputPath(const std::string& path) {
  const std::string e = detail::lowerExtension(path);
  return e == ".png" || e == ".exr" || e == ".hdr";
}

Result<std::pair<int, int>> parseSize(std::string_view text) {
  int w = 0, h = 0;
  char x = 0, tail = 0;
  const std::string s(text);
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &tail) != 3 || (x != 'x' && x != 'X') ||
      w < 1 || h < 1) {
    return makeError("size must be WxH, e.g. 1280x720 (got '" + s + "')");
  }
  return std::make_pair(w, h);
}

Result<BatchJob> parseBatchJob(std::string_view text, int line, const JobRequest& defaults) {
  const json j = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return makeError(lineError(line, "not valid JSON"));
  if (!j.is_object()) return makeError(lineError(line, "not a JSON object"));
  BatchJob job;
  job.line = line;
  job.request = defaults;
  for (const auto& [key, value] : j.items()) {
    if (auto st = applyOption(job, key, value); !st) {
      return makeError(lineError(line, st.message()));
    }
  }
  if (job.request.scenePath.empty()) return makeError(lineError(line, "no \"scene\""));
  if (job.output.empty()) return makeError(lineError(line, "no \"output\""));
  if (!isImageOutputPath(job.output)) {
    return makeError(lineError(line, "output must end in .png, .exr or .hdr: " + job.output));
  }
  return job;
}

Result<BatchShard> parseShard(std::string_view text) {
  int i = 0, n = 0;
  char slash = 0, tail = 0;
  const std::string s(text);
  if (std::sscanf(s.c_str(), "%d%c%d%c", &i, &slash, &n, &tail) != 3 || slash != '/' || n < 1 ||
      i < 0 || i >= n) {
    return makeError("--shard must be I/N with 0 <= I < N, e.g. 0/4 (got '" + s + "')");
  }
  return BatchShard{i, n};
}

std::string batchResultJson(const BatchResult& r) {
  static constexpr const char* kStatus[] = {"ok", "failed", "skipped"};
  json j = {{"line", r.line},
            {"scene", r.scene},
            {"output", r.output},
            {"status", kStatus[static_cast<int>(r.status)]}};
  if (r.status == BatchResult::Status::Failed) j["error"] = r.error;
  if (r.status == BatchResult::Status::Ok) {
    j["load_seconds"] = std::round(r.loadSeconds * 1000.0) / 1000.0;
    j["render_seconds"] = std::round(r.renderSeconds * 1000.0) / 1000.0;
    j["frames"] = r.frames;
    j["size"] = {r.width, r.height};
    j["automatic"] = r.automatic;
    if (r.automatic) {
      j["converged"] = r.converged;
      j["error_estimate"] = std::round(r.errorEstimate * 1000.0) / 1000.0;
    }
    if (r.time) j["time"] = *r.time;
    const float* m = &r.camera.world[0][0];
    j["camera"] = {{"world", std::vector<float>(m, m + 16)},  // column-major camera-to-world
                   {"yfov", r.camera.yfov},
                   {"aspect", r.camera.aspect},
                   {"orthographic", r.camera.orthographic},
                   {"ymag", r.camera.ymag}};
  }
  j["warnings"] = r.warnings;
  // Replace, not throw, on invalid UTF-8 in a file name or message.
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace penumbra
