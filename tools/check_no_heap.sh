#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Usage: tools/check_no_heap.sh LIBRARY_ARCHIVE [NM]
#
# Checks two flight-code rules on a built library archive:
#   1. no heap, stdio or process-exit function is referenced (undefined
#      symbols), so the library runs without an allocator or a console;
#   2. no writable global or static data (.data, .bss, COMMON): all state
#      lives in caller-owned structs. Constant tables (.rodata, and
#      .data.rel.ro, which PIE builds use for tables of pointers) are fine.
# NM defaults to "nm"; use arm-none-eabi-nm for the cross archive.
set -euo pipefail

if [[ $# -lt 1 || $# -gt 2 || $1 == -h || $1 == --help ]]; then
  sed -n '2,10s/^# \{0,1\}//p' "$0"
  [[ $# -ge 1 && ( $1 == -h || $1 == --help ) ]] && exit 0
  exit 2
fi
archive=$1
nm_tool=${2:-nm}
[[ -f $archive ]] || { echo "check_no_heap: no such archive: $archive" >&2; exit 2; }
command -v "$nm_tool" >/dev/null || { echo "check_no_heap: '$nm_tool' not found" >&2; exit 2; }

# Heap (including newlib's reentrant _r variants), stdio and exit/abort.
forbidden='malloc|calloc|realloc|reallocarray|free|aligned_alloc|posix_memalign|memalign|valloc|pvalloc'
forbidden+='|sbrk|_sbrk|brk|_malloc_r|_calloc_r|_realloc_r|_free_r|_sbrk_r'
forbidden+='|printf|fprintf|sprintf|snprintf|vprintf|vfprintf|vsprintf|vsnprintf|dprintf|asprintf'
forbidden+='|iprintf|fiprintf|siprintf|sniprintf|__printf_chk|__fprintf_chk|__sprintf_chk|__snprintf_chk'
forbidden+='|__vfprintf_chk|__vsnprintf_chk|puts|fputs|putchar|putc|fputc|fwrite|fopen|fclose|fread'
forbidden+='|fflush|fgets|getchar|scanf|sscanf|fscanf|perror|stdin|stdout|stderr'
forbidden+='|_impure_ptr|_global_impure_ptr|__assert_fail|__assert_func|exit|_exit|abort|atexit'

# nm's System V format gives "name|value|class|type|size|line|section" and
# one "Symbols from archive[member]:" header per object.
report=$(LC_ALL=C "$nm_tool" --format=sysv "$archive" | awk -F'|' -v bad="^(${forbidden})\$" '
  function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
  /^Symbols from / { member = $0; sub(/^Symbols from /, "", member); sub(/:$/, "", member); next }
  NF < 7 { next }
  {
    name = trim($1); class = trim($3); section = trim($7)
    if (class == "U" && name ~ bad) {
      printf "  %s: uses %s (heap/stdio/exit)\n", member, name
    } else if (class != "U" && (class == "C" || section == "*COM*" ||
               (section ~ /^\.(data|bss|sdata|sbss|tdata|tbss)(\.|$)/ && section !~ /^\.data\.rel\.ro/))) {
      printf "  %s: writable data %s (class %s, section %s)\n", member, name, class, section
    }
  }')

if [[ -n $report ]]; then
  echo "check_no_heap: FAILED for $archive:"
  echo "$report"
  exit 1
fi
echo "check_no_heap: OK for $archive (no heap/stdio/exit references, no writable data)"
