// The target that builds the tests' precompiled header (tests/CMakeLists.txt,
// looptess_test_pch); every test target reuses it. Nothing else is here.
