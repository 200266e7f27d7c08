// The program lineloc_test_pch compiles the GoogleTest binaries' precompiled
// header for (tests/support/CMakeLists.txt); it is never run.
int main() {
  return 0;
}
