// The definitions of load_flags.h: the load options' flags, from the schema.

#include "load_flags.h"

#include <stdexcept>

namespace massprops::app {
namespace {

// The schema's check as a CLI11 validator: the message is the library's, after the flag.
CLI::Validator SchemaCheck(const LoadOptionSpec& spec) {
  return CLI::Validator(
      [&spec](std::string& text) -> std::string {
        std::string problem;
        const auto read = ReadOptionText(spec, text, problem);
        if (!read) return problem;
        LoadOptions scratch;
        return SetLoadOption(scratch, spec, *read).value_or("");
      },
      "", "");
}

std::string HelpOf(const LoadOptionSpec& spec, std::string_view prefix) {
  std::string help = std::string(prefix) + std::string(spec.help);
  if (spec.type == OptionType::kChoice) {
    help += ": ";
    for (std::size_t i = 0; i < spec.choices.size(); ++i) help += (i ? ", " : "") + spec.choices[i];
  }
  return help;
}

}  // namespace

LoadFlags::LoadFlags(CLI::App& app, std::initializer_list<std::string_view> keys, std::string_view help_prefix) {
  for (std::string_view key : keys) {
    const LoadOptionSpec* spec = FindLoadOption(key);
    if (!spec) throw std::logic_error("no load option '" + std::string(key) + "' in the schema");
    Entry& e = entries_.emplace_back();
    e.spec = spec;
    const std::string flag(spec->flag);
    if (spec->type == OptionType::kSwitch) {
      e.option = app.add_flag(flag, e.on, HelpOf(*spec, help_prefix));
    } else {
      e.option = app.add_option(flag, e.text, HelpOf(*spec, help_prefix))->check(SchemaCheck(*spec));
      if (!spec->default_text.empty() && spec->key != "unit") e.option->default_str(spec->default_text);
      e.option->type_name(spec->type == OptionType::kChoice ? "NAME" : spec->type == OptionType::kCount ? "INT" : "X");
    }
  }
  const Entry *density = Find("density"), *mass = Find("mass");
  if (density && mass) mass->option->excludes(density->option);
}

const LoadFlags::Entry* LoadFlags::Find(std::string_view key) const {
  for (const Entry& e : entries_)
    if (e.spec->key == key) return &e;
  return nullptr;
}

CLI::Option* LoadFlags::Flag(std::string_view key) const {
  const Entry* e = Find(key);
  if (!e) throw std::logic_error("no flag for '" + std::string(key) + "' declared");
  return e->option;
}

bool LoadFlags::Given(std::string_view key) const {
  const Entry* e = Find(key);
  return e && e->option->count() > 0;
}

void LoadFlags::Apply(LoadOptions& options) const {
  for (const Entry& e : entries_) {
    if (e.option->count() == 0) continue;
    OptionValue value = true;
    std::string problem;
    if (e.spec->type != OptionType::kSwitch) value = ReadOptionText(*e.spec, e.text, problem).value_or(value);
    if (const auto set = SetLoadOption(options, *e.spec, value)) problem = *set;
    if (!problem.empty()) {
      throw std::logic_error(std::string(e.spec->flag) + ": " + problem);  // the validator admitted it
    }
  }
}

}  // namespace massprops::app
