#include "objscan/io/ply.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "objscan/common/error.h"
#include "objscan/io/atomic_file.h"

namespace objscan::io {
namespace {

// ---------------------------------------------------------------- writing

template <class T>
void AppendRaw(std::string* out, T value) {
  // PLY binary_little_endian; the hosts we build for are little-endian (checked below).
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->append(bytes, sizeof(T));
}

void AppendFloatText(std::string* out, float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  out->append(buffer);
}

void CheckPlyData(const std::string& path, const PlyData& data) {
  const std::size_t n = data.points.size();
  if (!data.normals.empty() && data.normals.size() != n) {
    throw InputError(path + ": cannot write PLY: " + std::to_string(data.normals.size()) + " normals for " +
                     std::to_string(n) + " points");
  }
  if (!data.colors.empty() && data.colors.size() != n) {
    throw InputError(path + ": cannot write PLY: " + std::to_string(data.colors.size()) + " colours for " +
                     std::to_string(n) + " points");
  }
  for (const auto& [name, values] : data.int_properties) {
    if (values.size() != n) {
      throw InputError(path + ": cannot write PLY: property '" + name + "' has " + std::to_string(values.size()) +
                       " values for " + std::to_string(n) + " points");
    }
  }
  // Face indices are checked as the faces are written (PlyStreamWriter::AddTriangle).
}

// The file goes out in chunks of about this size: a scene's map is tens of MB, which need not sit
// in memory a second time at the end of a run, when the map is at its largest.
constexpr std::size_t kPlyChunkBytes = std::size_t{1} << 20;

void CheckLittleEndian(const std::string& path) {
  static_assert(sizeof(float) == 4 && sizeof(std::int32_t) == 4, "PLY writer assumes 32-bit float/int");
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  if (first != 1) throw InputError(path + ": binary PLY writing needs a little-endian host");
}

void CheckLayout(const std::string& path, const PlyLayout& layout) {
  for (const auto& name : layout.int_properties) {
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos) {
      throw InputError(path + ": cannot write PLY: bad property name '" + name + "'");
    }
  }
  for (const auto& comment : layout.comments) {
    // A line break would end the comment and start a header line readers reject.
    if (comment.find_first_of("\r\n") != std::string::npos) {
      throw InputError(path + ": cannot write PLY: a header comment spans lines (starts '" +
                       comment.substr(0, comment.find_first_of("\r\n")) + "')");
    }
  }
}

}  // namespace

struct PlyStreamWriter::Impl {
  Impl(const std::string& path, PlyLayout l) : layout(std::move(l)), file(path) {}
  PlyLayout layout;
  AtomicFileWriter file;
  std::string buffer;
  std::size_t vertices = 0, triangles = 0;

  void Flush() {
    file.Write(buffer.data(), buffer.size());
    buffer.clear();
  }
  void MaybeFlush() {
    if (buffer.size() >= kPlyChunkBytes) Flush();
  }
};

PlyStreamWriter::PlyStreamWriter(const std::string& path, PlyLayout layout) {
  CheckLittleEndian(path);
  CheckLayout(path, layout);
  impl_ = std::make_unique<Impl>(path, std::move(layout));
  Impl& w = *impl_;
  const PlyLayout& l = w.layout;
  w.buffer.reserve(kPlyChunkBytes + 4096);
  std::string& out = w.buffer;
  out += "ply\n";
  out += l.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
  out += "comment written by objscan\n";
  for (const auto& comment : l.comments) {
    if (comment != "written by objscan") out += "comment " + comment + "\n";  // a file read back keeps one
  }
  out += "element vertex " + std::to_string(l.num_vertices) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  if (l.normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
  if (l.colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (const auto& name : l.int_properties) out += "property int " + name + "\n";
  if (l.num_triangles > 0) {
    out += "element face " + std::to_string(l.num_triangles) + "\n";
    out += "property list uchar int vertex_indices\n";
  }
  out += "end_header\n";
}

PlyStreamWriter::~PlyStreamWriter() = default;

void PlyStreamWriter::AddVertex(const Eigen::Vector3f& point, const Eigen::Vector3f& normal,
                                const std::array<std::uint8_t, 3>& color, const std::int32_t* ints) {
  Impl& w = *impl_;
  const PlyLayout& l = w.layout;
  if (w.vertices == l.num_vertices || w.triangles > 0) {
    throw InputError(w.file.path() + ": cannot write PLY: more than the " + std::to_string(l.num_vertices) +
                     " vertices announced, or a vertex after the faces");
  }
  ++w.vertices;
  w.MaybeFlush();
  std::string& out = w.buffer;
  const std::size_t n_ints = l.int_properties.size();
  if (l.binary) {
    for (int k = 0; k < 3; ++k) AppendRaw(&out, point[k]);
    if (l.normals) {
      for (int k = 0; k < 3; ++k) AppendRaw(&out, normal[k]);
    }
    if (l.colors) out.append(reinterpret_cast<const char*>(color.data()), 3);
    for (std::size_t k = 0; k < n_ints; ++k) AppendRaw(&out, ints[k]);
    return;
  }
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out += ' ';
    AppendFloatText(&out, point[k]);
  }
  if (l.normals) {
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      AppendFloatText(&out, normal[k]);
    }
  }
  if (l.colors) {
    for (int k = 0; k < 3; ++k) out += ' ' + std::to_string(static_cast<int>(color[k]));
  }
  for (std::size_t k = 0; k < n_ints; ++k) out += ' ' + std::to_string(ints[k]);
  out += '\n';
}

void PlyStreamWriter::AddTriangle(const Eigen::Vector3i& t) {
  Impl& w = *impl_;
  const PlyLayout& l = w.layout;
  if (w.vertices != l.num_vertices || w.triangles == l.num_triangles) {
    throw InputError(w.file.path() + ": cannot write PLY: a face before the " + std::to_string(l.num_vertices) +
                     " vertices, or more than the " + std::to_string(l.num_triangles) + " faces announced");
  }
  for (int k = 0; k < 3; ++k) {
    if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= l.num_vertices) {
      throw InputError(w.file.path() + ": cannot write PLY: triangle index " + std::to_string(t[k]) + " out of range");
    }
  }
  ++w.triangles;
  w.MaybeFlush();
  std::string& out = w.buffer;
  if (l.binary) {
    AppendRaw(&out, static_cast<std::uint8_t>(3));
    for (int k = 0; k < 3; ++k) AppendRaw(&out, static_cast<std::int32_t>(t[k]));
  } else {
    out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) + '\n';
  }
}

void PlyStreamWriter::Commit() {
  Impl& w = *impl_;
  if (w.vertices != w.layout.num_vertices || w.triangles != w.layout.num_triangles) {
    throw InputError(w.file.path() + ": cannot write PLY: " + std::to_string(w.vertices) + " of " +
                     std::to_string(w.layout.num_vertices) + " vertices and " + std::to_string(w.triangles) + " of " +
                     std::to_string(w.layout.num_triangles) + " faces given");
  }
  w.Flush();
  w.file.Commit();
}

PlyLayout LayoutOf(const PlyData& data, bool binary) {
  PlyLayout layout;
  layout.num_vertices = data.points.size();
  layout.normals = !data.normals.empty();
  layout.colors = !data.colors.empty();
  for (const auto& prop : data.int_properties) layout.int_properties.push_back(prop.first);
  layout.num_triangles = data.triangles.size();
  layout.comments = data.comments;
  layout.binary = binary;
  return layout;
}

void WritePly(const std::string& path, const PlyData& data, bool binary) {
  CheckLittleEndian(path);
  CheckPlyData(path, data);
  PlyStreamWriter writer(path, LayoutOf(data, binary));
  const Eigen::Vector3f no_normal = Eigen::Vector3f::Zero();
  const std::array<std::uint8_t, 3> no_color = {0, 0, 0};
  std::vector<std::int32_t> ints(data.int_properties.size());
  for (std::size_t i = 0; i < data.points.size(); ++i) {
    for (std::size_t k = 0; k < ints.size(); ++k) ints[k] = data.int_properties[k].second[i];
    writer.AddVertex(data.points[i], data.normals.empty() ? no_normal : data.normals[i],
                     data.colors.empty() ? no_color : data.colors[i], ints.data());
  }
  for (const auto& t : data.triangles) writer.AddTriangle(t);
  writer.Commit();
}

// ---------------------------------------------------------------- reading

namespace {

enum class Format { kAscii, kBinaryLittle, kBinaryBig };
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct Property {
  std::string name;
  Type type = Type::kFloat32;
  bool is_list = false;
  Type count_type = Type::kUint8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

bool ParseType(const std::string& s, Type* type) {
  if (s == "char" || s == "int8") *type = Type::kInt8;
  else if (s == "uchar" || s == "uint8") *type = Type::kUint8;
  else if (s == "short" || s == "int16") *type = Type::kInt16;
  else if (s == "ushort" || s == "uint16") *type = Type::kUint16;
  else if (s == "int" || s == "int32") *type = Type::kInt32;
  else if (s == "uint" || s == "uint32") *type = Type::kUint32;
  else if (s == "float" || s == "float32") *type = Type::kFloat32;
  else if (s == "double" || s == "float64") *type = Type::kFloat64;
  else return false;
  return true;
}

std::size_t TypeSize(Type t) {
  switch (t) {
    case Type::kInt8: case Type::kUint8: return 1;
    case Type::kInt16: case Type::kUint16: return 2;
    case Type::kInt32: case Type::kUint32: case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 1;
}

bool IsIntegerType(Type t) { return t != Type::kFloat32 && t != Type::kFloat64; }

// Reads values of the body one by one, in ASCII or binary.
class BodyReader {
 public:
  BodyReader(const std::string& path, const std::string& file, std::size_t offset, Format format)
      : path_(path), file_(file), pos_(offset), format_(format) {}

  double Next(Type type) {
    if (format_ == Format::kAscii) return NextText();
    const std::size_t size = TypeSize(type);
    if (pos_ + size > file_.size()) throw InputError(path_ + ": bad PLY: file is truncated");
    unsigned char bytes[8];
    std::memcpy(bytes, file_.data() + pos_, size);
    pos_ += size;
    if (format_ == Format::kBinaryBig) {
      for (std::size_t i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    }
    switch (type) {
      case Type::kInt8: { std::int8_t v; std::memcpy(&v, bytes, 1); return v; }
      case Type::kUint8: return bytes[0];
      case Type::kInt16: { std::int16_t v; std::memcpy(&v, bytes, 2); return v; }
      case Type::kUint16: { std::uint16_t v; std::memcpy(&v, bytes, 2); return v; }
      case Type::kInt32: { std::int32_t v; std::memcpy(&v, bytes, 4); return v; }
      case Type::kUint32: { std::uint32_t v; std::memcpy(&v, bytes, 4); return v; }
      case Type::kFloat32: { float v; std::memcpy(&v, bytes, 4); return v; }
      case Type::kFloat64: { double v; std::memcpy(&v, bytes, 8); return v; }
    }
    return 0.0;
  }

 private:
  double NextText() {
    while (pos_ < file_.size() && std::isspace(static_cast<unsigned char>(file_[pos_]))) ++pos_;
    if (pos_ >= file_.size()) throw InputError(path_ + ": bad PLY: file is truncated");
    const char* begin = file_.c_str() + pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) {
      std::size_t stop = pos_;
      while (stop < file_.size() && !std::isspace(static_cast<unsigned char>(file_[stop])) && stop - pos_ < 20) ++stop;
      throw InputError(path_ + ": bad PLY: '" + file_.substr(pos_, stop - pos_) + "' is not a number");
    }
    pos_ += static_cast<std::size_t>(end - begin);
    return v;
  }

  const std::string& path_;
  const std::string& file_;
  std::size_t pos_;
  Format format_;
};

std::string ReadWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path + ": cannot open PLY file");
  // One read of the file's size (a stream iterator goes byte by byte: most of a large binary
  // file's read time); a stream without a size (a pipe) is read the slow way.
  const std::streamoff size = in.tellg();
  if (size < 0) {
    in.clear();
    in.seekg(0);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::string file(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(file.data(), size)) throw InputError(path + ": cannot read PLY file");
  return file;
}

// A value read from the file as a 32-bit integer: false for NaN, an infinity, a fraction or a value
// outside int32's range (converting those is undefined behaviour).
bool ToInt32(double value, std::int32_t* out) {
  if (!(value >= -2147483648.0 && value <= 2147483647.0) || value != std::floor(value)) return false;
  *out = static_cast<std::int32_t>(value);
  return true;
}

// A list's length as read from the file: a whole number in [0, max] (NaN fails both comparisons).
bool ListLength(double value, double max, long* out) {
  if (!(value >= 0.0 && value <= max) || value != std::floor(value)) return false;
  *out = static_cast<long>(value);
  return true;
}

int FindProperty(const Element& e, const char* name) {
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    if (e.properties[i].name == name && !e.properties[i].is_list) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

PlyData ReadPly(const std::string& path) {
  const std::string file = ReadWhole(path);
  const auto bad = [&path](const std::string& what) { return InputError(path + ": bad PLY: " + what); };

  // Header: lines up to "end_header".
  std::size_t pos = 0;
  auto next_line = [&](std::string* line) {
    if (pos >= file.size()) return false;
    std::size_t end = file.find('\n', pos);
    if (end == std::string::npos) end = file.size();
    *line = file.substr(pos, end - pos);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos = end + 1;
    return true;
  };
  std::string line;
  if (!next_line(&line) || line != "ply") throw bad("missing 'ply' magic line");
  Format format = Format::kAscii;
  bool have_format = false;
  bool have_end = false;
  std::vector<Element> elements;
  std::vector<std::string> comments;
  while (next_line(&line)) {
    std::istringstream ss(line);
    std::string keyword;
    ss >> keyword;
    if (keyword == "comment") {
      comments.push_back(line.size() > 8 ? line.substr(8) : std::string());
      continue;
    }
    if (keyword.empty() || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      have_end = true;
      break;
    }
    if (keyword == "format") {
      std::string name, version;
      ss >> name >> version;
      if (name == "ascii") format = Format::kAscii;
      else if (name == "binary_little_endian") format = Format::kBinaryLittle;
      else if (name == "binary_big_endian") format = Format::kBinaryBig;
      else throw bad("unknown format '" + name + "'");
      have_format = true;
    } else if (keyword == "element") {
      Element e;
      long long count = -1;
      ss >> e.name >> count;
      if (e.name.empty() || count < 0 || ss.fail()) throw bad("malformed line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) throw bad("property before any element");
      Property p;
      std::string type;
      ss >> type;
      if (type == "list") {
        std::string count_type, item_type;
        ss >> count_type >> item_type >> p.name;
        p.is_list = true;
        if (!ParseType(count_type, &p.count_type) || !ParseType(item_type, &p.type) || p.name.empty()) {
          throw bad("malformed line '" + line + "'");
        }
      } else {
        ss >> p.name;
        if (!ParseType(type, &p.type) || p.name.empty()) throw bad("malformed line '" + line + "'");
      }
      elements.back().properties.push_back(p);
    } else {
      throw bad("unknown header line '" + line + "'");
    }
  }
  if (!have_end) throw bad("no end_header");
  if (!have_format) throw bad("no format line");

  // A header announcing more data than the file can hold is truncated (and must not make us
  // allocate for it): every scalar takes at least its size in binary, two characters in ASCII.
  {
    double min_bytes = 0;
    for (const Element& e : elements) {
      double per_row = 0;
      for (const Property& p : e.properties) {
        per_row += format == Format::kAscii ? 2.0 : static_cast<double>(TypeSize(p.is_list ? p.count_type : p.type));
      }
      min_bytes += per_row * static_cast<double>(e.count);
    }
    if (min_bytes > static_cast<double>(file.size() - std::min(pos, file.size())) + 1.0) {
      throw bad("file is truncated (the header announces more data than the file holds)");
    }
  }
  PlyData data;
  data.comments = std::move(comments);
  BodyReader body(path, file, pos, format);
  bool have_vertices = false;
  for (const Element& e : elements) {
    if (e.name == "vertex" && !have_vertices) {
      have_vertices = true;
      const int ix = FindProperty(e, "x"), iy = FindProperty(e, "y"), iz = FindProperty(e, "z");
      if (ix < 0 || iy < 0 || iz < 0) throw bad("vertex element lacks x, y or z");
      const int inx = FindProperty(e, "nx"), iny = FindProperty(e, "ny"), inz = FindProperty(e, "nz");
      const bool normals = inx >= 0 && iny >= 0 && inz >= 0;
      int ir = FindProperty(e, "red"), ig = FindProperty(e, "green"), ib = FindProperty(e, "blue");
      if (ir < 0 && ig < 0 && ib < 0) {
        ir = FindProperty(e, "r");
        ig = FindProperty(e, "g");
        ib = FindProperty(e, "b");
      }
      const bool colors = ir >= 0 && ig >= 0 && ib >= 0;
      // Integer properties other than colours become int_properties, in header order.
      std::vector<int> slot(e.properties.size(), -1);
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        const int pi = static_cast<int>(i);
        if (p.is_list || !IsIntegerType(p.type)) continue;
        if (pi == ix || pi == iy || pi == iz || pi == inx || pi == iny || pi == inz) continue;
        if ((colors && (pi == ir || pi == ig || pi == ib)) || p.name == "alpha") continue;
        slot[i] = static_cast<int>(data.int_properties.size());
        data.int_properties.emplace_back(p.name, std::vector<std::int32_t>());
        data.int_properties.back().second.reserve(e.count);
      }
      data.points.resize(e.count);
      if (normals) data.normals.resize(e.count);
      if (colors) data.colors.resize(e.count);
      std::vector<double> values(e.properties.size());
      for (std::size_t v = 0; v < e.count; ++v) {
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          const Property& p = e.properties[i];
          if (p.is_list) {
            long count = 0;
            if (!ListLength(body.Next(p.count_type), 1e7, &count)) {
              throw bad("vertex " + std::to_string(v) + " has a bad list length for '" + p.name + "'");
            }
            for (long k = 0; k < count; ++k) body.Next(p.type);
            continue;
          }
          values[i] = body.Next(p.type);
        }
        data.points[v] = Eigen::Vector3f(values[ix], values[iy], values[iz]);
        if (normals) data.normals[v] = Eigen::Vector3f(values[inx], values[iny], values[inz]);
        if (colors) {
          const bool unit = !IsIntegerType(e.properties[ir].type);  // float colours in [0, 1]
          for (int k = 0; k < 3; ++k) {
            const double c = values[k == 0 ? ir : (k == 1 ? ig : ib)] * (unit ? 255.0 : 1.0);
            // Clamped before rounding: NaN (fails both comparisons) and huge values have no long.
            const double clamped = c > 255.0 ? 255.0 : (c >= 0.0 ? c : 0.0);
            data.colors[v][k] = static_cast<std::uint8_t>(std::lround(clamped));
          }
        }
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          if (slot[i] < 0) continue;
          std::int32_t value = 0;
          if (!ToInt32(values[i], &value)) {
            throw bad("vertex " + std::to_string(v) + " property '" + e.properties[i].name + "' is not a 32-bit integer");
          }
          data.int_properties[slot[i]].second.push_back(value);
        }
      }
    } else if (e.name == "face") {
      int list_index = -1;
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) list_index = static_cast<int>(i);
      }
      if (list_index < 0) throw bad("face element lacks vertex_indices");
      data.triangles.reserve(e.count);
      std::vector<int> polygon;
      for (std::size_t f = 0; f < e.count; ++f) {
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          const Property& p = e.properties[i];
          if (!p.is_list) {
            body.Next(p.type);
            continue;
          }
          long count = 0;
          if (!ListLength(body.Next(p.count_type), 1e6, &count)) {
            throw bad("face " + std::to_string(f) + " has a bad vertex count");
          }
          if (static_cast<int>(i) != list_index) {
            for (long k = 0; k < count; ++k) body.Next(p.type);
            continue;
          }
          polygon.clear();
          for (long k = 0; k < count; ++k) {
            std::int32_t index = 0;
            if (!ToInt32(body.Next(p.type), &index)) {
              throw bad("face " + std::to_string(f) + " has a vertex index that is not a 32-bit integer");
            }
            polygon.push_back(index);
          }
          // Polygons are split into a triangle fan.
          for (std::size_t k = 2; k < polygon.size(); ++k) {
            data.triangles.emplace_back(polygon[0], polygon[k - 1], polygon[k]);
          }
        }
      }
    } else {
      // An element without properties holds no bytes, whatever its count: nothing to skip (a count
      // of 10^12 would otherwise loop for hours over nothing; the size check above cannot catch it).
      if (e.properties.empty()) continue;
      for (std::size_t r = 0; r < e.count; ++r) {
        for (const Property& p : e.properties) {
          if (p.is_list) {
            long count = 0;
            if (!ListLength(body.Next(p.count_type), 1e7, &count)) {
              throw bad("element '" + e.name + "' has a bad list length");
            }
            for (long k = 0; k < count; ++k) body.Next(p.type);
          } else {
            body.Next(p.type);
          }
        }
      }
    }
  }
  if (!have_vertices) throw bad("no vertex element");
  for (const auto& t : data.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= data.points.size()) {
        throw bad("face index " + std::to_string(t[k]) + " out of range");
      }
    }
  }
  return data;
}

}  // namespace objscan::io
