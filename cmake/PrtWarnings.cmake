# One INTERFACE target that carries the project's warnings, architecture and sanitizer flags.
# No -ffast-math: numerics are checked against tolerances and NaN handling is explicit.
add_library(prt_options INTERFACE)
target_compile_options(prt_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual
  -Wno-unused-parameter)
if(PRT_ARCH)
  target_compile_options(prt_options INTERFACE -march=${PRT_ARCH})
endif()
if(PRT_SANITIZE)
  target_compile_options(prt_options INTERFACE -fsanitize=${PRT_SANITIZE} -fno-omit-frame-pointer
    -fno-sanitize-recover=all)
  target_link_options(prt_options INTERFACE -fsanitize=${PRT_SANITIZE})
endif()
if(PRT_BUILD_FUZZ)
  # Coverage feedback for libFuzzer in every prt library; the fuzz targets add libFuzzer's main.
  target_compile_options(prt_options INTERFACE -fsanitize=fuzzer-no-link)
endif()
if(PRT_COVERAGE)
  # clang source-based coverage: each run writes a .profraw (LLVM_PROFILE_FILE) for llvm-profdata/llvm-cov.
  target_compile_options(prt_options INTERFACE -fprofile-instr-generate -fcoverage-mapping)
  target_link_options(prt_options INTERFACE -fprofile-instr-generate)
endif()
