// Where twinrender finds what it ships beside the program: its default scenes, their particle
// files, the example shaders and the docs (the resource folder), and the OpenImageIO module.
// Both are found from the program's own location, so an installed tree (`cmake --install`,
// the Debian package) works from any working folder and wherever its prefix is:
//   PREFIX/bin/twinrender
//   PREFIX/share/twinrender/{scenes,data,examples,docs,ci}   (the resource folder)
//   PREFIX/lib/twinrender/twinrender_oiio.so                 (lib/<multiarch>/ on Debian)
// A build tree keeps the same shape below the build folder for the module (every program is
// one folder deep: build/app/twinrender, build/lib/twinrender/), and takes the source folder
// it was built from as its resource folder. A program of a build tree finds that tree and its
// source folder at run time (the first folder above it holding CMakeCache.txt, and the
// CMAKE_HOME_DIRECTORY written there), so no compile line names a folder of one clone and a
// compiler cache serves every clone alike.
#pragma once

#include <filesystem>

namespace twinrender::core {

// The folder of the running program (/proc/self/exe, links resolved).
std::filesystem::path programDir();

// The resource folder: PREFIX/share/twinrender beside an installed program when it holds
// scenes/, else the source folder of this build.
std::filesystem::path resourceDir();

// The build tree the running program belongs to (its test binaries too), and the source folder
// it was configured from. Throw core::InputError for a program outside any build tree.
std::filesystem::path buildDir();
std::filesystem::path sourceDir();

// The OpenImageIO module's path, beside the program as installed or built.
std::filesystem::path oiioModulePath();

}  // namespace twinrender::core
