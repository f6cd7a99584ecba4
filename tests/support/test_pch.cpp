// The target that builds the tests' precompiled headers (tests/CMakeLists.txt,
// looptess_test_pch and, in the sanitizer build, looptess_test_pch_O0); every test
// target reuses one. Nothing else is here.
