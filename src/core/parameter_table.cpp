#include "core/parameter_table.hpp"

#include <cstdio>
#include <vector>

namespace clothlab {

std::string parameter_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  // "1e-09" -> "1e-9", "1e+09" -> "1e9": the exponent as a reader writes it.
  std::string number;
  bool in_exponent = false, leading = false;
  for (const char* c = text; *c != '\0'; ++c) {
    if (*c == 'e') {
      in_exponent = leading = true;
    } else if (in_exponent && leading && (*c == '+' || *c == '0')) {
      continue;
    } else if (in_exponent && *c != '-') {
      leading = false;
    }
    number += *c;
  }
  return number;
}

field_ref field_of_any_stage(const parameter& p, const stage_structs& structs) {
  for (const stage_kind stage : {stage_kind::spring, stage_kind::coupled, stage_kind::cloth}) {
    if (const field_ref field = p.field(structs, stage))
      return field;
  }
  return {};
}

std::string range_text(const parameter& p, bool unit) {
  if (p.high == unbounded)
    return format(tr("at least %s"), parameter_number(p.low).c_str());
  std::string text =
      format(tr("%s to %s"), parameter_number(p.low).c_str(), parameter_number(p.high).c_str());
  if (unit && !p.unit.empty()) {
    text += ' ';
    text += p.unit;
  }
  return text;
}

std::string default_text(const parameter& p) {
  if (!p.off.empty())
    return tr(p.off.data());
  single_spring_parameters spring;
  coupled_springs_parameters coupled;
  cloth_parameters cloth;
  const stage_structs defaults{spring, coupled, cloth};
  struct stage_default {
    const char* name;
    field_ref field;
  };
  std::vector<stage_default> values;
  for (const auto& [stage, name] :
       {std::pair{stage_kind::spring, tr("spring")}, std::pair{stage_kind::coupled, tr("chain")},
        std::pair{stage_kind::cloth, tr("cloth")}}) {
    if (const field_ref field = p.field(defaults, stage))
      values.push_back({name, field});
  }
  bool same = true;
  for (const stage_default& v : values)
    same = same && v.field.get() == values.front().field.get();
  if (same)
    return parameter_number(values.front().field.get());
  // "spring and chain 0.01, cloth 0.002": neighbours with the same default are named together.
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const bool joins_next =
        i + 1 < values.size() && values[i + 1].field.get() == values[i].field.get();
    text += values[i].name;
    text += joins_next ? std::string(tr(" and ")) : ' ' + parameter_number(values[i].field.get());
    if (!joins_next && i + 1 < values.size())
      text += ", ";
  }
  return text;
}

std::string help_text(const parameter& p) {
  std::string text(tr(p.help.data()));
  if (!p.unit.empty())
    text += ", " + std::string(p.unit);
  return text + colon() + range_text(p, false) + " [" + default_text(p) + "]";
}

std::string doc_row(const parameter& p) {
  std::string meaning(p.doc);
  const std::pair<std::string, std::string> fills[] = {
      {"{range}", range_text(p)},
      {"{default}", default_text(p)},
      {"{slider_high}", parameter_number(p.slider.high)}};
  for (const auto& [placeholder, value] : fills) {
    for (std::size_t at = meaning.find(placeholder); at != std::string::npos;
         at = meaning.find(placeholder, at + value.size()))
      meaning.replace(at, placeholder.size(), value);
  }
  // The document writes m/s² where the command line's messages write m/s^2.
  for (std::size_t at = meaning.find("^2"); at != std::string::npos; at = meaning.find("^2"))
    meaning.replace(at, 2, "²");
  return "| `" + std::string(p.option) + " " + std::string(p.value_name) + "` | " + meaning + " |";
}

}  // namespace clothlab
