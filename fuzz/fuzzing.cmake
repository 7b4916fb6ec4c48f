# TESSERA_FUZZ (top-level option, default OFF): a libFuzzer build of the whole project (fuzz/README.md).
# Included by the top-level CMakeLists.txt before any library is added, because the instrumentation must
# cover the libraries, not only the fuzz targets.
#
# With clang and a working libFuzzer (Debian: clang + libclang-rt-14-dev, `bash tools/bootstrap.sh --fuzz`),
# every C++ file is compiled with -fsanitize=fuzzer-no-link,address,undefined (coverage feedback plus
# ASan and UBSan, UBSan made fatal so that libFuzzer reports it), everything links with
# -fsanitize=address,undefined, and fuzz/CMakeLists.txt links each fuzz_<target> with -fsanitize=fuzzer.
# With another compiler or without libFuzzer the option says so and changes nothing: no flags, no fuzz
# targets, the build goes on. TESSERA_FUZZ_ENABLED tells fuzz/CMakeLists.txt which case it is in.
set(TESSERA_FUZZ_ENABLED OFF)
if(NOT TESSERA_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(WARNING "TESSERA_FUZZ=ON needs clang for libFuzzer, but the C++ compiler is ${CMAKE_CXX_COMPILER_ID} "
                  "${CMAKE_CXX_COMPILER_VERSION}: no fuzz targets are built (the replay tests still are). "
                  "Use `make fuzz`, or configure with -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "
                  "(install them with `bash tools/bootstrap.sh --fuzz`).")
  return()
endif()
include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_FLAGS "-fsanitize=fuzzer,address,undefined")
set(CMAKE_REQUIRED_QUIET ON)
check_cxx_source_compiles([[
#include <cstddef>
#include <cstdint>
extern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }
]] TESSERA_HAVE_LIBFUZZER)
unset(CMAKE_REQUIRED_FLAGS)
unset(CMAKE_REQUIRED_QUIET)
if(NOT TESSERA_HAVE_LIBFUZZER)
  message(WARNING "TESSERA_FUZZ=ON: ${CMAKE_CXX_COMPILER} cannot link a libFuzzer target with "
                  "-fsanitize=fuzzer,address,undefined (on Debian the runtime is in libclang-rt-14-dev; "
                  "`bash tools/bootstrap.sh --fuzz` installs it): no fuzz targets are built.")
  return()
endif()
set(TESSERA_FUZZ_ENABLED ON)
message(STATUS "TESSERA_FUZZ: libFuzzer targets enabled (fuzz/README.md)")
add_compile_options("$<$<COMPILE_LANGUAGE:CXX>:-fsanitize=fuzzer-no-link,address,undefined>"
                    "$<$<COMPILE_LANGUAGE:CXX>:-fno-sanitize-recover=undefined>"
                    "$<$<COMPILE_LANGUAGE:CXX>:-fno-omit-frame-pointer>")
add_link_options(-fsanitize=address,undefined)
