# Run at build time (cmake -P): writes OUT, a source file defining contact::git_revision(), from
# `git describe` in SOURCE_DIR, and rewrites it only when the revision changed, so a commit between
# builds reaches meta.json without a reconfigure and an unchanged tree rebuilds nothing.
execute_process(COMMAND git describe --always --dirty --abbrev=12
                WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT revision)
  set(revision "unknown")
endif()
set(content "// Generated at build time by cmake/git_revision.cmake.\nnamespace contact {\nconst char* git_revision() { return \"${revision}\"; }\n}  // namespace contact\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL content)
  file(WRITE "${OUT}" "${content}")
endif()
