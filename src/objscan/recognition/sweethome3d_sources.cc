#include "objscan/recognition/sweethome3d_sources.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <set>

#include "objscan/common/error.h"
#include "objscan/io/sweethome3d.h"
#include "objscan/io/zip_archive.h"

namespace objscan::recognition {
namespace fs = std::filesystem;
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Lower case, characters other than [a-z0-9._-] as '-', runs of '-' as one, none at either end.
std::string Sanitized(const std::string& text) {
  std::string out;
  for (const char ch : Lower(text)) {
    const auto c = static_cast<unsigned char>(ch);
    const bool keep = std::isalnum(c) || c == '.' || c == '_' || c == '-';
    if (keep && c < 0x80) {
      out += ch;
    } else if (!out.empty() && out.back() != '-') {
      out += '-';
    }
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "piece" : out;
}

}  // namespace

bool IsSweetHome3dSpec(const std::string& spec) {
  return spec == "sweethome3d" || Lower(fs::path(spec).extension().string()) == ".sh3f";
}

std::vector<std::string> SweetHome3dCatalogsOf(const std::string& spec) {
  if (spec == "sweethome3d") return io::SweetHome3dCatalogFiles(io::SweetHome3dCatalogDir());
  std::error_code ec;
  if (!fs::is_regular_file(spec, ec)) throw InputError(spec + ": Sweet Home 3D catalog not found");
  return {spec};
}

SweetHome3dSources SweetHome3dModelSources(const std::vector<std::string>& catalog_files, const io::CategoryMap& map) {
  SweetHome3dSources result;
  std::set<std::string> names;
  for (const std::string& file : catalog_files) {
    std::error_code ec;
    const std::string absolute = fs::absolute(file, ec).lexically_normal().string();
    const io::SweetHome3dCatalog catalog = io::LoadSweetHome3dCatalog(absolute);
    const std::string stem = Sanitized(fs::path(absolute).stem().string());
    SweetHome3dCatalogSummary summary;
    summary.file = absolute;
    summary.name = catalog.name;
    summary.license = catalog.license;
    summary.license_text = catalog.license_text;
    summary.pieces = static_cast<int>(catalog.pieces.size());
    for (const io::SweetHome3dPiece& piece : catalog.pieces) {
      io::ModelIdentity identity;
      identity.name = piece.name;
      identity.labels = {piece.category};
      identity.uris = {piece.model};
      identity.model_id = piece.id;
      identity.source_dir = fs::path(absolute).parent_path().string();
      const std::string described = stem + ": " + piece.id + " (" + piece.name + ", " + piece.category + ")";
      const std::optional<io::CategoryRuleMatch> match = map.Match(identity);
      if (!match) {
        result.unmatched.push_back(described);
        continue;
      }
      if (match->skip || !match->category) {
        result.skipped.push_back(described);
        continue;
      }
      const world::Category category = *match->category;
      const std::size_t hash = piece.id.rfind('#');
      const std::string id_part = hash == std::string::npos || hash + 1 == piece.id.size() ? piece.id : piece.id.substr(hash + 1);
      const std::string base = std::string(world::CategoryName(category)) + "/sh3d-" + stem + "-" + Sanitized(id_part);
      std::string name = base;
      if (names.count(name) > 0) name = base + "-" + std::to_string(piece.index);
      for (int k = 2; names.count(name) > 0; ++k) name = base + "-" + std::to_string(piece.index) + "-" + std::to_string(k);
      names.insert(name);

      ModelSource s;
      s.category = category;
      s.name = name;
      s.source = io::SweetHome3dSource(absolute, piece.id);
      auto shared_piece = std::make_shared<const io::SweetHome3dPiece>(piece);
      s.load_mesh = [absolute, shared_piece] {
        return io::LoadSweetHome3dMesh(io::ZipArchive::Open(absolute), *shared_piece);
      };
      s.support_heights_m = {piece.elevation_cm > 0.0 ? static_cast<float>(piece.elevation_cm / 100.0) : 0.0f};
      s.creator = piece.creator;
      s.license = catalog.license;
      result.sources.push_back(std::move(s));
      ++result.models_per_category[world::CategoryName(category)];
      ++summary.models;
    }
    result.catalogs.push_back(std::move(summary));
  }
  return result;
}

}  // namespace objscan::recognition
