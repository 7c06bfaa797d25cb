// SPDX-License-Identifier: MIT
#include "network_json.hpp"

#include <cmath>
#include <map>

#include <nlohmann/json.hpp>

#include "../core/input_file.hpp"
#include "../core/json_path.hpp"

namespace odeskin {
namespace {

using nlohmann::json;

Status fail(const std::string& path, const std::string& problem) {
  return parseError((path.empty() ? std::string("(top level)") : path) + ": " + problem);
}

// Follows the SAX events to know which field the parser was reading when it stopped: nlohmann's own
// messages give only line and column, and a NaN written as a bare literal stops it mid-object.
class PathTracker : public JsonPathSax {
 public:
  bool key(string_t& k) override {
    if (JsonPathSax::key(k)) return true;
    error_ = fail(path(), "appears twice in its object");
    return false;
  }
  bool parse_error(std::size_t, const std::string& last_token, const nlohmann::detail::exception& ex) override {
    std::string what = ex.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 9: ..." -> from "line" on.
    if (const std::size_t at = what.find("line "); at != std::string::npos) what = what.substr(at);
    else if (const std::size_t close = what.find("] "); close != std::string::npos) what = what.substr(close + 2);
    // nlohmann's message usually quotes the last token already.
    if (what.find("last read") == std::string::npos) what += "; last read '" + last_token + "'";
    error_ = fail(path(), "invalid JSON (" + what + ")" +
                              (last_token.find_first_of("NI") != std::string::npos
                                   ? " - JSON has no NaN or Infinity, give a finite number"
                                   : ""));
    return false;
  }
  const Status& error() const { return error_; }

 private:
  Status error_;
};

Status checkKeys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  if (!object.is_object()) return fail(path, std::string("expected an object, got ") + object.type_name());
  for (const auto& [key, value] : object.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      return fail(jsonChild(path, key), "unknown field (expected one of: " + list + ")");
    }
  }
  return okStatus();
}

Result<const json*> required(const json& object, const std::string& path, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) return fail(jsonChild(path, key), "missing");
  return &*it;
}

// A value as an error message shows it: itself when it is a scalar, else its kind. Never dump() a
// container from the file: dump recurses one stack frame per level, and a few hundred kilobytes of
// nested arrays overflow the stack (odeskin surface crashed on such a "columns").
std::string shown(const json& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size()) + (value.size() == 1 ? " element" : " elements");
  if (value.is_object()) return "an object";
  return value.dump();
}

Result<double> number(const json& value, const std::string& path) {
  if (!value.is_number()) return fail(path, std::string("expected a number, got ") + value.type_name());
  const double x = value.get<double>();
  if (!std::isfinite(x)) return fail(path, "not a finite number");
  return x;
}

Result<std::uint32_t> count(const json& value, const std::string& path, std::uint32_t minimum) {
  if (!value.is_number_integer() || value.get<std::int64_t>() < minimum || value.get<std::int64_t>() > 1 << 24) {
    return fail(path, "expected an integer in [" + std::to_string(minimum) + ", 16777216], got " + shown(value));
  }
  return static_cast<std::uint32_t>(value.get<std::int64_t>());
}

Result<std::string> text(const json& value, const std::string& path) {
  if (!value.is_string()) return fail(path, std::string("expected a string, got ") + value.type_name());
  return value.get<std::string>();
}

Result<bool> flag(const json& object, const std::string& path, const char* key, bool fallback) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_boolean()) return fail(jsonChild(path, key), std::string("expected true or false, got ") + it->type_name());
  return it->get<bool>();
}

Result<std::vector<double>> numbers(const json& value, const std::string& path, std::size_t size) {
  if (!value.is_array() || value.size() != size) {
    return fail(path, "expected an array of " + std::to_string(size) + " numbers, got " + shown(value));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < size; ++i) {
    ODESKIN_ASSIGN_OR_RETURN(const double x, number(value[i], jsonElement(path, i)));
    out.push_back(x);
  }
  return out;
}

Result<Ode6Shape> shape(const json& object, const std::string& path, bool with_place) {
  if (with_place) {
    ODESKIN_TRY(checkKeys(object, path, {"row", "column", "rho", "eta", "lambda"}));
  } else {
    ODESKIN_TRY(checkKeys(object, path, {"rho", "eta", "lambda"}));
  }
  Ode6Shape s;
  double* fields[3] = {&s.rho, &s.eta, &s.lambda};
  const char* names[3] = {"rho", "eta", "lambda"};
  for (int i = 0; i < 3; ++i) {
    ODESKIN_ASSIGN_OR_RETURN(const json* value, required(object, path, names[i]));
    ODESKIN_ASSIGN_OR_RETURN(*fields[i], number(*value, jsonChild(path, names[i])));
  }
  return s;
}

using CurveIndex = std::map<std::string, std::uint32_t>;

Result<std::uint32_t> curveRef(const json& value, const std::string& path, const CurveIndex& curves) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string name, text(value, path));
  const auto it = curves.find(name);
  if (it == curves.end()) return fail(path, "no curve named '" + name + "' in \"curves\"");
  return it->second;
}

Status readCurves(const json& root, NetworkDescription& d, CurveIndex& index) {
  ODESKIN_ASSIGN_OR_RETURN(const json* curves, required(root, "", "curves"));
  if (!curves->is_object() || curves->empty()) return fail("curves", "expected an object of named curves");
  for (const auto& [name, curve] : curves->items()) {
    const std::string path = jsonChild("curves", name);
    ODESKIN_TRY(checkKeys(curve, path, {"points", "closed"}));
    ODESKIN_ASSIGN_OR_RETURN(const json* points, required(curve, path, "points"));
    const std::string points_path = jsonChild(path, "points");
    if (!points->is_array()) return fail(points_path, std::string("expected an array of [x, y, z], got ") + points->type_name());
    std::vector<Vec3> xyz;
    for (std::size_t i = 0; i < points->size(); ++i) {
      ODESKIN_ASSIGN_OR_RETURN(const std::vector<double> p, numbers((*points)[i], jsonElement(points_path, i), 3));
      xyz.emplace_back(p[0], p[1], p[2]);
    }
    ODESKIN_ASSIGN_OR_RETURN(const bool closed, flag(curve, path, "closed", false));
    if (xyz.size() < (closed ? 3u : 2u)) {
      return fail(points_path, std::to_string(xyz.size()) + " points; a" + (closed ? " closed" : "n open") +
                                   " curve needs at least " + (closed ? "3" : "2"));
    }
    index[name] = static_cast<std::uint32_t>(d.curve_names.size());
    d.curve_names.push_back(name);
    d.curve_points.push_back(std::move(xyz));
    d.curve_closed.push_back(closed);
  }
  return okStatus();
}

Status readDerivatives(const json& value, const std::string& path, const CurveIndex& curves, NetworkBoundary& b) {
  ODESKIN_TRY(checkKeys(value, path, {"coefficients", "controls", "at", "side", "slopes", "first", "second"}));
  const bool coefficients = value.contains("coefficients");
  const bool controls = value.contains("controls");
  const bool given = value.contains("first") || value.contains("second");
  if (coefficients + controls + given != 1) {
    return fail(path, "give exactly one of \"coefficients\": [w1, w2], \"controls\" with \"at\", or \"first\" "
                      "and \"second\" curves");
  }
  if (coefficients) {
    ODESKIN_ASSIGN_OR_RETURN(const std::vector<double> w, numbers(value["coefficients"], jsonChild(path, "coefficients"), 2));
    b.source = DerivativeSource::kCoefficients;
    b.w_first = w[0];
    b.w_second = w[1];
    return okStatus();
  }
  if (given) {
    ODESKIN_ASSIGN_OR_RETURN(const json* first, required(value, path, "first"));
    ODESKIN_ASSIGN_OR_RETURN(const json* second, required(value, path, "second"));
    b.source = DerivativeSource::kCurves;
    ODESKIN_ASSIGN_OR_RETURN(b.first_curve, curveRef(*first, jsonChild(path, "first"), curves));
    ODESKIN_ASSIGN_OR_RETURN(b.second_curve, curveRef(*second, jsonChild(path, "second"), curves));
    return okStatus();
  }
  b.source = DerivativeSource::kControlCurves;
  const json& names = value["controls"];
  const std::string names_path = jsonChild(path, "controls");
  if (!names.is_array() || names.size() != 2) return fail(names_path, "expected two curve names, in increasing u");
  ODESKIN_ASSIGN_OR_RETURN(b.control_lower, curveRef(names[0], jsonElement(names_path, 0), curves));
  ODESKIN_ASSIGN_OR_RETURN(b.control_upper, curveRef(names[1], jsonElement(names_path, 1), curves));
  ODESKIN_ASSIGN_OR_RETURN(const json* at, required(value, path, "at"));
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<double> u, numbers(*at, jsonChild(path, "at"), 2));
  for (std::size_t i = 0; i < 2; ++i) {
    if (!(u[i] > 0.0 && u[i] < 1.0)) return fail(jsonElement(jsonChild(path, "at"), i), "u = " + json(u[i]).dump() + " is outside (0, 1)");
  }
  if (!(u[0] < u[1])) return fail(jsonChild(path, "at"), "the two u must increase");
  b.u_lower = u[0];
  b.u_upper = u[1];
  ODESKIN_ASSIGN_OR_RETURN(const json* side, required(value, path, "side"));
  ODESKIN_ASSIGN_OR_RETURN(const std::string side_text, text(*side, jsonChild(path, "side")));
  if (side_text != "after" && side_text != "before") {
    return fail(jsonChild(path, "side"), "expected \"after\" (in the patch that starts here) or \"before\" (the one that ends here)");
  }
  b.side = side_text == "after" ? ControlSide::kAfter : ControlSide::kBefore;
  if (value.contains("slopes")) {
    ODESKIN_ASSIGN_OR_RETURN(const std::string slopes, text(value["slopes"], jsonChild(path, "slopes")));
    if (slopes != "one-sided" && slopes != "three-point") return fail(jsonChild(path, "slopes"), "expected \"one-sided\" or \"three-point\"");
    b.slopes = slopes == "one-sided" ? SlopeRule::kOneSided : SlopeRule::kThreePoint;
  }
  return okStatus();
}

Status readBoundaries(const json& root, const CurveIndex& curves, NetworkDescription& d) {
  ODESKIN_ASSIGN_OR_RETURN(const json* boundaries, required(root, "", "boundaries"));
  if (!boundaries->is_array()) return fail("boundaries", "expected an array in u order");
  for (std::size_t i = 0; i < boundaries->size(); ++i) {
    const json& value = (*boundaries)[i];
    const std::string path = jsonElement("boundaries", i);
    ODESKIN_TRY(checkKeys(value, path, {"name", "curve", "derivatives"}));
    NetworkBoundary b;
    if (value.contains("name")) {
      ODESKIN_ASSIGN_OR_RETURN(b.name, text(value["name"], jsonChild(path, "name")));
    }
    ODESKIN_ASSIGN_OR_RETURN(const json* curve, required(value, path, "curve"));
    ODESKIN_ASSIGN_OR_RETURN(b.position, curveRef(*curve, jsonChild(path, "curve"), curves));
    ODESKIN_ASSIGN_OR_RETURN(const json* derivatives, required(value, path, "derivatives"));
    ODESKIN_TRY(readDerivatives(*derivatives, jsonChild(path, "derivatives"), curves, b));
    d.boundaries.push_back(std::move(b));
  }
  const std::size_t minimum = d.closed_u ? 1 : 2;
  if (d.boundaries.size() < minimum) {
    return fail("boundaries", std::to_string(d.boundaries.size()) + " boundaries; " +
                                  (d.closed_u ? "a network closed in u needs at least 1" : "an open network needs at least 2"));
  }
  return okStatus();
}

Status readShapes(const json& root, NetworkDescription& d) {
  const std::uint32_t rows = static_cast<std::uint32_t>(d.closed_u ? d.boundaries.size() : d.boundaries.size() - 1);
  ODESKIN_ASSIGN_OR_RETURN(const json* base, required(root, "", "shape"));
  ODESKIN_ASSIGN_OR_RETURN(const Ode6Shape all, shape(*base, "shape", false));
  // Refused before the per-patch shapes are allocated: columns alone may be up to 2^24.
  const std::uint64_t patches = std::uint64_t{rows} * d.columns;
  if (patches > kMaxNetworkPatches) {
    return fail("columns", std::to_string(rows) + " rows x " + std::to_string(d.columns) + " columns = " +
                               std::to_string(patches) + " patches, more than the " +
                               std::to_string(kMaxNetworkPatches) + " a network may have");
  }
  d.shapes.assign(static_cast<std::size_t>(patches), all);
  if (root.contains("row_shapes")) {
    const json& list = root["row_shapes"];
    if (!list.is_array() || list.size() != rows) {
      return fail("row_shapes", "expected one shape per row (" + std::to_string(rows) + "), got " +
                                    std::to_string(list.is_array() ? list.size() : 0));
    }
    for (std::uint32_t r = 0; r < rows; ++r) {
      ODESKIN_ASSIGN_OR_RETURN(const Ode6Shape s, shape(list[r], jsonElement("row_shapes", r), false));
      std::fill_n(d.shapes.begin() + std::ptrdiff_t{r} * d.columns, d.columns, s);
    }
  }
  if (root.contains("patch_shapes")) {
    const json& list = root["patch_shapes"];
    if (!list.is_array()) return fail("patch_shapes", "expected an array of {row, column, rho, eta, lambda}");
    std::map<std::uint64_t, std::size_t> given;  // patch -> the entry that shaped it
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = jsonElement("patch_shapes", i);
      ODESKIN_ASSIGN_OR_RETURN(const Ode6Shape s, shape(list[i], path, true));
      ODESKIN_ASSIGN_OR_RETURN(const json* row_value, required(list[i], path, "row"));
      ODESKIN_ASSIGN_OR_RETURN(const json* column_value, required(list[i], path, "column"));
      ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t row, count(*row_value, jsonChild(path, "row"), 0));
      ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t column, count(*column_value, jsonChild(path, "column"), 0));
      if (row >= rows || column >= d.columns) {
        return fail(path, "patch (" + std::to_string(row) + ", " + std::to_string(column) + ") is outside the " +
                              std::to_string(rows) + " x " + std::to_string(d.columns) + " network");
      }
      // A second entry for one patch would win silently, by its place in the list.
      const std::uint64_t patch = std::uint64_t{row} * d.columns + column;
      if (const auto earlier = given.find(patch); earlier != given.end()) {
        return fail(path, "patch (" + std::to_string(row) + ", " + std::to_string(column) + ") is already shaped by " +
                              jsonElement("patch_shapes", earlier->second));
      }
      given[patch] = i;
      d.shapes[patch] = s;
    }
  }
  return okStatus();
}

json shapeJson(const Ode6Shape& s) { return json{{"rho", s.rho}, {"eta", s.eta}, {"lambda", s.lambda}}; }

}  // namespace

Result<NetworkDescription> parseNetworkDescription(std::string_view text_view) {
  PathTracker tracker;
  if (!json::sax_parse(text_view, &tracker)) return tracker.error();
  const json root = json::parse(text_view);
  ODESKIN_TRY(checkKeys(root, "", {"version", "description", "columns", "closed_u", "continuity", "curves",
                                   "boundaries", "shape", "row_shapes", "patch_shapes"}));
  ODESKIN_ASSIGN_OR_RETURN(const json* version, required(root, "", "version"));
  if (*version != kNetworkJsonVersion) return fail("version", "expected 1, got " + shown(*version));
  NetworkDescription d;
  ODESKIN_ASSIGN_OR_RETURN(const json* columns, required(root, "", "columns"));
  ODESKIN_ASSIGN_OR_RETURN(d.columns, count(*columns, "columns", 1));
  ODESKIN_ASSIGN_OR_RETURN(d.closed_u, flag(root, "", "closed_u", false));
  if (root.contains("continuity")) {
    ODESKIN_ASSIGN_OR_RETURN(const std::string policy, text(root["continuity"], "continuity"));
    if (policy != "refuse" && policy != "warn") return fail("continuity", "expected \"refuse\" or \"warn\"");
    d.continuity = policy == "warn" ? ContinuityPolicy::kWarn : ContinuityPolicy::kRefuse;
  }
  if (root.contains("description")) {
    ODESKIN_TRY(text(root["description"], "description").status());
  }
  CurveIndex curves;
  ODESKIN_TRY(readCurves(root, d, curves));
  ODESKIN_TRY(readBoundaries(root, curves, d));
  ODESKIN_TRY(readShapes(root, d));
  return d;
}

Result<NetworkDescription> readNetworkDescription(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string content, readInputFile(path));
  Result<NetworkDescription> d = parseNetworkDescription(content);
  if (!d.ok()) return Status(d.status().code(), path.string() + ": " + d.status().message());
  return d;
}

Result<Network> loadNetwork(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  ODESKIN_ASSIGN_OR_RETURN(NetworkDescription d, readNetworkDescription(path));
  Result<Network> network = Network::build(std::move(d), warnings);
  if (!network.ok()) return Status(network.status().code(), path.string() + ": " + network.status().message());
  return network;
}

std::string networkJson(const NetworkDescription& d) {
  nlohmann::ordered_json root;
  root["version"] = kNetworkJsonVersion;
  root["columns"] = d.columns;
  if (d.closed_u) root["closed_u"] = true;
  if (d.continuity == ContinuityPolicy::kWarn) root["continuity"] = "warn";
  nlohmann::ordered_json curves = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < d.curve_names.size(); ++i) {
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const Vec3& p : d.curve_points[i]) points.push_back({p.x, p.y, p.z});
    curves[d.curve_names[i]] = {{"points", points}};
    if (d.curve_closed[i]) curves[d.curve_names[i]]["closed"] = true;
  }
  root["curves"] = curves;
  nlohmann::ordered_json boundaries = nlohmann::ordered_json::array();
  for (const NetworkBoundary& b : d.boundaries) {
    nlohmann::ordered_json entry;
    if (!b.name.empty()) entry["name"] = b.name;
    entry["curve"] = d.curve_names[b.position];
    nlohmann::ordered_json derivatives;
    switch (b.source) {
      case DerivativeSource::kCoefficients:
        derivatives["coefficients"] = {b.w_first, b.w_second};
        break;
      case DerivativeSource::kCurves:
        derivatives["first"] = d.curve_names[b.first_curve];
        derivatives["second"] = d.curve_names[b.second_curve];
        break;
      case DerivativeSource::kControlCurves:
        derivatives["controls"] = {d.curve_names[b.control_lower], d.curve_names[b.control_upper]};
        derivatives["at"] = {b.u_lower, b.u_upper};
        derivatives["side"] = b.side == ControlSide::kAfter ? "after" : "before";
        derivatives["slopes"] = b.slopes == SlopeRule::kOneSided ? "one-sided" : "three-point";
        break;
    }
    entry["derivatives"] = derivatives;
    boundaries.push_back(entry);
  }
  root["boundaries"] = boundaries;
  const Ode6Shape first = d.shapes.empty() ? Ode6Shape{} : d.shapes[0];
  root["shape"] = shapeJson(first);
  nlohmann::ordered_json patches = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < d.shapes.size(); ++p) {
    const Ode6Shape& s = d.shapes[p];
    if (s.rho == first.rho && s.eta == first.eta && s.lambda == first.lambda) continue;
    nlohmann::ordered_json entry = {{"row", p / d.columns}, {"column", p % d.columns}};
    entry["rho"] = s.rho;
    entry["eta"] = s.eta;
    entry["lambda"] = s.lambda;
    patches.push_back(entry);
  }
  if (!patches.empty()) root["patch_shapes"] = patches;
  return root.dump(1) + "\n";
}

}  // namespace odeskin
