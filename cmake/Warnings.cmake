# Warnings for project code only (dependencies come in as SYSTEM includes through their targets).
# Precise floating point on purpose: no -ffast-math anywhere, because a reference must not depend
# on the compiler's reassociation.
add_library(shadowref_warnings INTERFACE)
target_compile_options(shadowref_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wdouble-promotion
  # GCC 12 reports impossible memcpy overlaps inside libstdc++'s std::string operator+ at -O3
  # (GCC bug 105651, fixed in 13): a false positive in a system header, not in our code.
  $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>)
add_library(shadowref::warnings ALIAS shadowref_warnings)

if(SHADOWREF_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
# ThreadSanitizer (preset `tsan`, reliability/run_tsan.sh): our code and the inline parts of the
# headers we include; Debian's libtbb, Embree and Mesa are not instrumented (reliability/README.md).
if(SHADOWREF_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
