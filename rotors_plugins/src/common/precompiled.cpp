// The translation unit that builds precompiled.h for the plugin libraries (CMakeLists.txt).
