#pragma once
// Where objscan's own files are: the config/ folder (default.yaml, paper.yaml, category maps, the
// SUNCG class table), which `cmake --install` puts in share/objscan/config.
#include <string>

namespace objscan::io {

// The config/ folder, the first of:
//  1. $OBJSCAN_CONFIG_DIR when set and not empty;
//  2. running from the build tree (the binary or libobjscan.so holding this code lies below the
//     build folder): the source tree's config/;
//  3. otherwise (installed): share/objscan/config relative to that binary (bin/) or library (lib/),
//     so an installed tree works wherever it is moved; the path is returned even when missing, so
//     errors name where the file was looked for.
std::string ConfigDir();
// `path` when absolute, else ConfigDir()/path.
std::string ResolveConfigPath(const std::string& path);

// The file this code was loaded from: the objscan program, the libobjscan shared library or the
// program objscan's static libraries are linked into; empty when unknown.
std::string LoadedModulePath();

}  // namespace objscan::io
