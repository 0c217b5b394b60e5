# SPDX-License-Identifier: BSD-3-Clause
# Size reports (text/data/bss).
#   ladrc_size                   target: totals of the library archive
#   ladrc_print_image_size(tgt)  prints a linked image's size after each link
include_guard(GLOBAL)

if(NOT CMAKE_SIZE)
  find_program(CMAKE_SIZE NAMES size)
endif()

if(CMAKE_SIZE)
  add_custom_target(ladrc_size
    COMMAND "${CMAKE_SIZE}" -t "$<TARGET_FILE:ladrc>"
    DEPENDS ladrc
    COMMENT "Size of the ladrc library (text/data/bss per object, then totals)"
    VERBATIM)
endif()

function(ladrc_print_image_size target)
  if(CMAKE_SIZE)
    add_custom_command(TARGET ${target} POST_BUILD
      COMMAND "${CMAKE_SIZE}" "$<TARGET_FILE:${target}>"
      VERBATIM)
  endif()
endfunction()
