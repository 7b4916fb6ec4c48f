// The sanitizer build's default ASan options, compiled into every program of that build (an OBJECT
// library linked to every target, CMakeLists.txt), so that a test run by hand behaves as under ctest.
// ASAN_OPTIONS still overrides any of them. Not in any other build.
//
// intercept_tls_get_addr=0: the sanitizer runtime of GCC up to 13 takes a dynamic TLS block that
// starts 16 bytes into a page for a pre-2.25 glibc block with a header, and reads the two words before
// it as the block's range. glibc's malloc puts a block there by chance, and LeakSanitizer's exit check
// then faults scanning a garbage range ("Tracer caught signal 11", after the test passed). Only
// dlopened libraries use dynamic TLS here: the image module with OpenImageIO, and Mesa's driver.
// The cost: dynamic TLS is not scanned for pointers (CONTRIBUTING.md, "Code", has the rest).
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
