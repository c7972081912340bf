# Writes OUT: a C++ function FUNC returning every file matching PATTERN, embedded as raw strings,
# so the binary carries its rule data and shader library with it.
file(GLOB files ${PATTERN})
list(SORT files)
set(body "// Generated from ${PATTERN} by embed_files.cmake; do not edit.\n#include \"core/embedded.h\"\nnamespace lwc {\nconst std::vector<EmbeddedFile>& ${FUNC}() {\n  static const std::vector<EmbeddedFile> files = {\n")
foreach(f ${files})
  get_filename_component(name ${f} NAME)
  file(READ ${f} text)
  string(APPEND body "    {\"${name}\", R\"lwcfile(${text})lwcfile\"},\n")
endforeach()
string(APPEND body "  };\n  return files;\n}\n}  // namespace lwc\n")
file(WRITE ${OUT}.tmp "${body}")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
