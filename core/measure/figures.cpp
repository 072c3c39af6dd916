#include "core/measure/figures.h"

namespace rtiow {

std::string figures_text(const Figures& value, int indent) {
  return value.dump(indent, ' ', false, Figures::error_handler_t::replace);
}

void write_figures(JsonWriter& out, const Figures& value) {
  switch (value.type()) {
    case Figures::value_t::object:
      out.begin_object();
      for (const auto& [key, member] : value.items()) write_figures(out.key(key), member);
      out.end();
      return;
    case Figures::value_t::array:
      out.begin_array();
      for (const Figures& element : value) write_figures(out, element);
      out.end();
      return;
    case Figures::value_t::string:
      out.string(value.get_ref<const std::string&>());
      return;
    case Figures::value_t::boolean:
      out.boolean(value.get<bool>());
      return;
    case Figures::value_t::number_integer:
      out.whole(value.get<std::int64_t>());
      return;
    case Figures::value_t::number_unsigned:
      out.whole(value.get<std::uint64_t>());
      return;
    case Figures::value_t::number_float:
      out.number(value.get<double>());
      return;
    default:  // null, and what JSON cannot hold, as nlohmann-json writes it
      out.null();
      return;
  }
}

}  // namespace rtiow
