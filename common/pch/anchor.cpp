// The one source of the precompiled-header donor targets (common/CMakeLists.txt): CMake
// compiles their precompiled headers alongside it, and every other target reuses those.
