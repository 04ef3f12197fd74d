// The request pieces that every shell writes as text or loose values
// (pipeline.h): pins as "VERTEX:U,V" (`--pin 12:0.5,0` on the command line,
// pins=["12:0.5,0"] in Python and in batch runs), and the weight blend from
// a method and the lambda and mu a user gave.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "intrinsic/error.h"
#include "intrinsic/pipeline.h"

namespace intrinsic {

FixedVertex parse_pin(const std::string& text, OptionSpelling spelling) {
  const auto bad = [&]() -> FixedVertex {
    const std::string example = spelling == OptionSpelling::Flag ? "--pin 12:0.5,0" : "'12:0.5,0' or (12, 0.5, 0)";
    throw_usage(option_label("pins", spelling) + " '" + text + "': expected VERTEX:U,V, e.g. " + example);
  };
  const size_t colon = text.find(':'), comma = text.find(',', colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || comma == std::string::npos) return bad();
  FixedVertex p{};
  const char* b = text.data();
  auto [end, ec] = std::from_chars(b, b + colon, p.vertex);
  if (ec != std::errc() || end != b + colon || colon == 0) return bad();
  auto number = [&](size_t from, size_t to, double& x) {
    // strtod, not from_chars<double>: the latter is missing from older libstdc++
    const std::string part = text.substr(from, to - from);
    char* stop = nullptr;
    x = std::strtod(part.c_str(), &stop);
    return !part.empty() && !std::isspace(static_cast<unsigned char>(part[0])) && stop == part.c_str() + part.size() &&
           std::isfinite(x);
  };
  if (!number(colon + 1, comma, p.uv.x()) || !number(comma + 1, text.size(), p.uv.y())) return bad();
  return p;
}

WeightOptions weight_options(Method method, std::optional<double> lambda, std::optional<double> mu,
                             OptionSpelling spelling) {
  const auto label = [&](std::string_view key) { return option_label(key, spelling); };
  WeightOptions w;
  w.method = method;
  if ((lambda || mu) && method != Method::Mixed)
    throw_usage(label("lambda") + " and " + label("mu") + " apply to " + label("method") + " mixed only");
  if (method == Method::Mixed) {
    if (!lambda && !mu) throw_usage(label("method") + " mixed needs " + label("lambda") + " and/or " + label("mu"));
    w.lambda = lambda.value_or(0.0);
    w.mu = mu.value_or(0.0);
    if (w.lambda == 0 && w.mu == 0) throw_usage(label("lambda") + " and " + label("mu") + " cannot both be zero");
  }
  return w;
}

}  // namespace intrinsic
