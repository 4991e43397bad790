# Writes OUT (a header with ROVING_VERSION and ROVING_COMMIT) from the project version and the
# git commit of SOURCE_DIR, on every build but touching the file only when the commit changed,
# so `roving --version` names the commit it was built from without needless rebuilds.
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR commit STREQUAL "")
  set(commit "unknown")
endif()
file(WRITE "${OUT}.tmp" "#pragma once\n#define ROVING_VERSION \"${VERSION}\"\n#define ROVING_COMMIT \"${commit}\"\n")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
