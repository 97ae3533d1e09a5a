// Command-line flags for every setting of the schema (penumbra/settings.h), for the tools'
// CLI11 parsers: names, help and ranges come from the schema, so a new setting gets its flag
// without touching a tool. Values are collected as (key, text) overrides for RenderJob.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "penumbra/settings.h"

namespace penumbra::tools {

// `--set KEY=VALUE` options as (key, text) overrides, appended to `out`; the first one without a
// key and '=' is returned in `bad` (false).
inline bool parseSetOptions(const std::vector<std::string>& sets,
                            std::vector<std::pair<std::string, std::string>>& out,
                            std::string& bad) {
  for (const auto& kv : sets) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      bad = kv;
      return false;
    }
    out.push_back({kv.substr(0, eq), kv.substr(eq + 1)});
  }
  return true;
}

class SettingFlags {
 public:
  // Adds one flag per schema entry that has one (under the group `group`).
  void add(CLI::App& app, const std::string& group = "Settings") {
    const RenderSettings defaults;
    for (const SettingInfo& info : settingsSchema()) {
      if (info.flag.empty()) continue;
      auto slot = std::make_unique<Slot>();
      slot->info = &info;
      const std::string flag(info.flag);
      std::string help(info.help);
      if (info.type == SettingType::Bool && flag.rfind("--no-", 0) == 0) {
        slot->option = app.add_flag(flag, slot->switched, "turn off: " + help)->group(group);
      } else if (info.type == SettingType::Bool) {
        slot->option = app.add_flag(flag, slot->switched, "turn on: " + help)->group(group);
      } else {
        help += " (" + settingRange(info) + "; default " + settingText(defaults, info) + ")";
        slot->option = app.add_option(flag, slot->text, help)->group(group);
      }
      slots_.push_back(std::move(slot));
    }
  }

  // The flags given on the command line, as RenderJob overrides.
  std::vector<std::pair<std::string, std::string>> overrides() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& s : slots_) {
      if (s->option->count() == 0) continue;
      const bool turnsOff = std::string_view(s->info->flag).rfind("--no-", 0) == 0;
      out.emplace_back(std::string(s->info->key),
                       s->switched ? (turnsOff ? "false" : "true") : s->text);
    }
    return out;
  }

 private:
  struct Slot {
    const SettingInfo* info = nullptr;
    CLI::Option* option = nullptr;
    std::string text;
    bool switched = false;
  };
  std::vector<std::unique_ptr<Slot>> slots_;
};

}  // namespace penumbra::tools
