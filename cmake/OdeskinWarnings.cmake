# One INTERFACE target carries the warning flags so no target sets them globally.
add_library(odeskin_warnings INTERFACE)
target_compile_options(odeskin_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
  $<$<BOOL:${ODESKIN_WERROR}>:-Werror>)
