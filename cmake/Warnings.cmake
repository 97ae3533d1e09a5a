# penumbra_warnings: the project's warning set, linked by every target we own.
add_library(penumbra_warnings INTERFACE)
target_compile_options(penumbra_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wnon-virtual-dtor
    -Wno-missing-field-initializers>
  $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CXX_COMPILER_ID:GNU>>:-Wshadow=local>
  $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra>)
option(PENUMBRA_WERROR "Treat warnings as errors" OFF)
if(PENUMBRA_WERROR)
  target_compile_options(penumbra_warnings INTERFACE -Werror)
endif()
