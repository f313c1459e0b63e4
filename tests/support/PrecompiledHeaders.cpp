// The translation unit that carries the tests' precompiled header (tests/CMakeLists.txt): it
// holds no code of its own.
