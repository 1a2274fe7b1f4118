#include "objscan/io/sweethome3d.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>

#include "objscan/common/error.h"
#include "objscan/io/mesh_io.h"
#include "objscan/io/zip_archive.h"

namespace objscan::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPropertiesEntry = "PluginFurnitureCatalog.properties";
constexpr const char* kLicenseEntry = "LICENSE.TXT";
constexpr const char* kDefaultCatalogDir = "/usr/share/sweethome3d/furniture";

void AppendUtf8(std::uint32_t cp, std::string* out) {
  if (cp < 0x80) {
    out->push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out->push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out->push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out->push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

bool IsPropertiesSpace(char c) { return c == ' ' || c == '\t' || c == '\f'; }

// Unescapes a key or value of a logical line into UTF-8 (the bytes are ISO-8859-1).
std::string Unescape(const std::string& raw, const std::string& where) {
  std::string out;
  out.reserve(raw.size());
  std::uint32_t high_surrogate = 0;
  const auto emit = [&](std::uint32_t unit) {
    if (high_surrogate != 0) {
      if (unit >= 0xDC00 && unit <= 0xDFFF) {
        AppendUtf8(0x10000 + ((high_surrogate - 0xD800) << 10) + (unit - 0xDC00), &out);
        high_surrogate = 0;
        return;
      }
      AppendUtf8(0xFFFD, &out);  // an unpaired high surrogate
      high_surrogate = 0;
    }
    if (unit >= 0xD800 && unit <= 0xDBFF) {
      high_surrogate = unit;
    } else if (unit >= 0xDC00 && unit <= 0xDFFF) {
      AppendUtf8(0xFFFD, &out);
    } else {
      AppendUtf8(unit, &out);
    }
  };
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const auto c = static_cast<unsigned char>(raw[i]);
    if (c != '\\' || i + 1 == raw.size()) {
      emit(c);
      continue;
    }
    const char e = raw[++i];
    switch (e) {
      case 't': emit('\t'); break;
      case 'n': emit('\n'); break;
      case 'r': emit('\r'); break;
      case 'f': emit('\f'); break;
      case 'u': {
        std::uint32_t unit = 0;
        for (int k = 0; k < 4; ++k) {
          const char h = i + 1 < raw.size() ? raw[++i] : '\0';
          if (!std::isxdigit(static_cast<unsigned char>(h))) throw InputError(where + ": malformed \\uXXXX escape");
          unit = unit * 16 + static_cast<std::uint32_t>(std::isdigit(static_cast<unsigned char>(h)) ? h - '0'
                                                                                                   : (std::tolower(h) - 'a' + 10));
        }
        emit(unit);
        break;
      }
      default: emit(static_cast<unsigned char>(e)); break;
    }
  }
  if (high_surrogate != 0) AppendUtf8(0xFFFD, &out);
  return out;
}

bool ParseDouble(const std::string& text, double* value) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(*begin))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(end[-1]))) --end;
  if (begin < end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  return ec == std::errc() && ptr == end && begin < end && std::isfinite(*value);
}

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

}  // namespace

std::map<std::string, std::string> ParseJavaProperties(const std::string& bytes, const std::string& where) {
  std::map<std::string, std::string> properties;
  std::size_t pos = 0;
  int line_number = 0;
  // The next natural line (without its terminator: \n, \r or \r\n); false at the end.
  const auto next_line = [&](std::string* line) {
    if (pos >= bytes.size()) return false;
    const std::size_t end = bytes.find_first_of("\r\n", pos);
    *line = bytes.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    pos = end == std::string::npos ? bytes.size() : end + 1;
    if (end != std::string::npos && bytes[end] == '\r' && pos < bytes.size() && bytes[pos] == '\n') ++pos;
    ++line_number;
    return true;
  };
  const auto strip_leading = [](const std::string& s) {
    std::size_t i = 0;
    while (i < s.size() && IsPropertiesSpace(s[i])) ++i;
    return s.substr(i);
  };
  const auto continues = [](const std::string& s) {
    std::size_t n = 0;
    for (std::size_t i = s.size(); i > 0 && s[i - 1] == '\\'; --i) ++n;
    return n % 2 == 1;
  };
  std::string natural;
  while (next_line(&natural)) {
    std::string line = strip_leading(natural);
    if (line.empty() || line[0] == '#' || line[0] == '!') continue;
    const int first_line = line_number;
    while (continues(line)) {
      line.pop_back();
      std::string more;
      if (!next_line(&more)) break;
      line += strip_leading(more);
    }
    std::size_t key_end = 0;
    while (key_end < line.size()) {
      const char c = line[key_end];
      if (c == '\\') {
        key_end += 2;
        continue;
      }
      if (c == '=' || c == ':' || IsPropertiesSpace(c)) break;
      ++key_end;
    }
    key_end = std::min(key_end, line.size());
    std::size_t value_begin = key_end;
    while (value_begin < line.size() && IsPropertiesSpace(line[value_begin])) ++value_begin;
    if (value_begin < line.size() && (line[value_begin] == '=' || line[value_begin] == ':')) ++value_begin;
    while (value_begin < line.size() && IsPropertiesSpace(line[value_begin])) ++value_begin;
    const std::string line_where = where + ": line " + std::to_string(first_line);
    properties[Unescape(line.substr(0, key_end), line_where)] = Unescape(line.substr(value_begin), line_where);
  }
  return properties;
}

const SweetHome3dPiece* SweetHome3dCatalog::Find(const std::string& piece_id) const {
  for (const SweetHome3dPiece& p : pieces) {
    if (p.id == piece_id) return &p;
  }
  return nullptr;
}

SweetHome3dCatalog LoadSweetHome3dCatalog(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": Sweet Home 3D catalog not found");
  const ZipArchive archive = ZipArchive::Open(path);
  if (!archive.Contains(kPropertiesEntry)) {
    throw InputError(path + ": no " + std::string(kPropertiesEntry) + " (not a Sweet Home 3D furniture catalog)");
  }
  const std::string where = path + ": " + kPropertiesEntry;
  const std::map<std::string, std::string> props = ParseJavaProperties(archive.Read(kPropertiesEntry), where);
  SweetHome3dCatalog catalog;
  catalog.file = path;
  const auto get = [&](const std::string& key) {
    const auto it = props.find(key);
    return it == props.end() ? std::string() : it->second;
  };
  catalog.id = get("id");
  catalog.name = get("name");
  catalog.license = get("license");
  if (archive.Contains(kLicenseEntry)) {
    // LICENSE.TXT is ISO-8859-1 text as the properties are.
    std::string text;
    for (const char c : archive.Read(kLicenseEntry)) AppendUtf8(static_cast<unsigned char>(c), &text);
    catalog.license_text = text;
  }

  // Pieces: every N of a key "<word>#N".
  std::set<int> indices;
  for (const auto& [key, value] : props) {
    const std::size_t hash = key.rfind('#');
    if (hash == std::string::npos || hash + 1 == key.size() || key.size() - hash > 9) continue;
    const std::string number = key.substr(hash + 1);
    if (!std::all_of(number.begin(), number.end(), [](unsigned char c) { return std::isdigit(c); })) continue;
    const std::string field = key.substr(0, hash);
    if (field == "id" || field == "name" || field == "model") indices.insert(std::stoi(number));
  }
  for (const int n : indices) {
    const std::string suffix = "#" + std::to_string(n);
    SweetHome3dPiece piece;
    piece.index = n;
    piece.id = get("id" + suffix);
    piece.name = get("name" + suffix);
    if (piece.id.empty()) piece.id = std::to_string(n);
    const std::string piece_where = where + ": piece " + std::to_string(n) + " ('" + piece.name + "')";
    piece.category = get("category" + suffix);
    piece.model = get("model" + suffix);
    if (piece.model.empty()) throw InputError(piece_where + ": no model" + suffix);
    if (piece.model.front() == '/') piece.model.erase(0, 1);
    const auto number = [&](const std::string& field, bool required, double* value) {
      const std::string text = get(field + suffix);
      if (text.empty() && !required) return;
      if (!ParseDouble(text, value)) {
        throw InputError(piece_where + ": " + field + suffix + " '" + text + "' is not a number");
      }
    };
    number("width", true, &piece.width_cm);
    number("depth", true, &piece.depth_cm);
    number("height", true, &piece.height_cm);
    number("elevation", false, &piece.elevation_cm);
    if (!(piece.width_cm > 0.0 && piece.depth_cm > 0.0 && piece.height_cm > 0.0)) {
      throw InputError(piece_where + ": width, depth and height must be positive");
    }
    const std::string rotation = get("modelRotation" + suffix);
    if (!rotation.empty()) {
      std::size_t p = 0;
      for (int k = 0; k < 9; ++k) {
        while (p < rotation.size() && std::isspace(static_cast<unsigned char>(rotation[p]))) ++p;
        std::size_t q = p;
        while (q < rotation.size() && !std::isspace(static_cast<unsigned char>(rotation[q]))) ++q;
        if (!ParseDouble(rotation.substr(p, q - p), &piece.model_rotation[k])) {
          throw InputError(piece_where + ": modelRotation" + suffix + " '" + rotation + "' is not 9 numbers");
        }
        p = q;
      }
      while (p < rotation.size() && std::isspace(static_cast<unsigned char>(rotation[p]))) ++p;
      if (p != rotation.size()) {
        throw InputError(piece_where + ": modelRotation" + suffix + " '" + rotation + "' is not 9 numbers");
      }
    }
    piece.door_or_window = Lower(get("doorOrWindow" + suffix)) == "true";
    piece.creator = get("creator" + suffix);
    catalog.pieces.push_back(std::move(piece));
  }
  return catalog;
}

geometry::TriangleMesh ParseObj(const std::string& text, const std::string& where) {
  geometry::TriangleMesh mesh;
  const char* p = text.data();
  const char* const end = text.data() + text.size();
  int line_number = 0;
  std::vector<int> corners;
  const auto fail = [&](const std::string& what) {
    throw InputError(where + ": line " + std::to_string(line_number) + ": " + what);
  };
  while (p < end) {
    ++line_number;
    const char* line_end = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (line_end == nullptr) line_end = end;
    const char* q = p;
    while (q < line_end && (*q == ' ' || *q == '\t')) ++q;
    const auto skip_space = [&] {
      while (q < line_end && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
    };
    if (line_end - q >= 2 && q[0] == 'v' && (q[1] == ' ' || q[1] == '\t')) {
      q += 2;
      Eigen::Vector3f v;
      for (int k = 0; k < 3; ++k) {
        skip_space();
        if (q < line_end && *q == '+') ++q;
        const auto [ptr, ec] = std::from_chars(q, line_end, v[k]);
        if (ec != std::errc() || !std::isfinite(v[k])) fail("malformed vertex");
        q = ptr;
      }
      mesh.vertices.push_back(v);
    } else if (line_end - q >= 2 && q[0] == 'f' && (q[1] == ' ' || q[1] == '\t')) {
      q += 2;
      corners.clear();
      const long n = static_cast<long>(mesh.vertices.size());
      while (true) {
        skip_space();
        if (q >= line_end) break;
        long index = 0;
        const auto [ptr, ec] = std::from_chars(q, line_end, index);
        if (ec != std::errc()) fail("malformed face");
        const long resolved = index > 0 ? index - 1 : n + index;
        if (index == 0 || resolved < 0 || resolved >= n) {
          fail("face index " + std::to_string(index) + " out of range (" + std::to_string(n) + " vertices so far)");
        }
        corners.push_back(static_cast<int>(resolved));
        q = ptr;
        while (q < line_end && *q != ' ' && *q != '\t' && *q != '\r') ++q;  // "/t/n"
      }
      for (std::size_t k = 2; k < corners.size(); ++k) {
        if (corners[0] == corners[k - 1] || corners[k - 1] == corners[k] || corners[0] == corners[k]) continue;
        mesh.triangles.emplace_back(corners[0], corners[k - 1], corners[k]);
      }
    }
    p = line_end + 1;
  }
  return mesh;
}

geometry::TriangleMesh PlaceSweetHome3dModel(const geometry::TriangleMesh& model, const SweetHome3dPiece& piece) {
  const std::array<double, 9>& r = piece.model_rotation;
  std::vector<Eigen::Vector3d> rotated(model.vertices.size());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (std::size_t i = 0; i < model.vertices.size(); ++i) {
    const Eigen::Vector3d v = model.vertices[i].cast<double>();
    rotated[i] = Eigen::Vector3d(r[0] * v.x() + r[1] * v.y() + r[2] * v.z(), r[3] * v.x() + r[4] * v.y() + r[5] * v.z(),
                                 r[6] * v.x() + r[7] * v.y() + r[8] * v.z());
    lo = lo.cwiseMin(rotated[i]);
    hi = hi.cwiseMax(rotated[i]);
  }
  const Eigen::Vector3d size_m(piece.width_cm / 100.0, piece.height_cm / 100.0, piece.depth_cm / 100.0);  // SH3D X, Y, Z
  Eigen::Vector3d scale = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double extent = hi[k] - lo[k];
    if (extent > 1e-12 * std::max(1.0, hi.cwiseAbs().maxCoeff())) scale[k] = size_m[k] / extent;
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  geometry::TriangleMesh mesh;
  mesh.triangles = model.triangles;
  mesh.vertices.resize(rotated.size());
  for (std::size_t i = 0; i < rotated.size(); ++i) {
    const Eigen::Vector3d& v = rotated[i];
    const double x = (v.x() - centre.x()) * scale.x();
    const double y = (v.y() - lo.y()) * scale.y();  // up, bottom on 0
    const double z = (v.z() - centre.z()) * scale.z();
    mesh.vertices[i] = Eigen::Vector3f(static_cast<float>(x), static_cast<float>(-z), static_cast<float>(y));
  }
  return mesh;
}

geometry::TriangleMesh LoadSweetHome3dMesh(const ZipArchive& archive, const SweetHome3dPiece& piece) {
  const std::string where = archive.path() + ": " + piece.model;
  const std::string bytes = archive.Read(piece.model);
  std::string extension = Lower(fs::path(piece.model).extension().string());
  if (!extension.empty()) extension.erase(0, 1);
  const geometry::TriangleMesh model =
      extension == "obj" ? ParseObj(bytes, where) : LoadMeshFromMemory(bytes, extension, where);
  if (model.triangles.empty()) throw InputError(where + ": model has no triangles");
  return PlaceSweetHome3dModel(model, piece);
}

geometry::TriangleMesh LoadSweetHome3dMesh(const std::string& catalog_path, const std::string& piece_id) {
  const SweetHome3dCatalog catalog = LoadSweetHome3dCatalog(catalog_path);
  const SweetHome3dPiece* piece = catalog.Find(piece_id);
  if (piece == nullptr) throw InputError(catalog_path + ": no piece of furniture with id '" + piece_id + "'");
  return LoadSweetHome3dMesh(ZipArchive::Open(catalog_path), *piece);
}

namespace {
constexpr const char* kSourcePrefix = "sweethome3d:";
}  // namespace

std::string SweetHome3dSource(const std::string& catalog_path, const std::string& piece_id) {
  return kSourcePrefix + catalog_path + "#" + piece_id;
}

bool IsSweetHome3dSource(const std::string& source) { return source.rfind(kSourcePrefix, 0) == 0; }

namespace {
// Where the catalog path of a source string ends (at its "#"); npos when it is not one.
std::size_t SourceCatalogEnd(const std::string& source) {
  if (!IsSweetHome3dSource(source)) return std::string::npos;
  const std::size_t at = Lower(source).find(".sh3f#", std::string(kSourcePrefix).size());
  return at == std::string::npos ? at : at + std::string(".sh3f").size();
}
}  // namespace

std::string SweetHome3dSourceCatalog(const std::string& source) {
  const std::size_t hash = SourceCatalogEnd(source);
  const std::size_t prefix = std::string(kSourcePrefix).size();
  return hash == std::string::npos ? std::string() : source.substr(prefix, hash - prefix);
}

geometry::TriangleMesh LoadSweetHome3dSource(const std::string& source) {
  const std::size_t hash = SourceCatalogEnd(source);
  if (hash == std::string::npos) {
    throw InputError("model source '" + source + "': not of the form sweethome3d:<catalog>.sh3f#<piece id>");
  }
  return LoadSweetHome3dMesh(SweetHome3dSourceCatalog(source), source.substr(hash + 1));
}

std::string SweetHome3dCatalogDir() {
  const char* env = std::getenv("OBJSCAN_SWEETHOME3D_DIR");
  return env != nullptr && env[0] != '\0' ? std::string(env) : std::string(kDefaultCatalogDir);
}

std::vector<std::string> SweetHome3dCatalogFiles(const std::string& dir) {
  std::error_code ec;
  const std::string hint = " (install Debian's sweethome3d-furniture package or set $OBJSCAN_SWEETHOME3D_DIR)";
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": Sweet Home 3D catalog folder not found" + hint);
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec) && Lower(entry.path().extension().string()) == ".sh3f") {
      files.push_back(entry.path().string());
    }
  }
  if (files.empty()) throw InputError(dir + ": no .sh3f Sweet Home 3D catalog in this folder" + hint);
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace objscan::io
