# The documentation's relative links resolve (tests/scripts/doc_links.sh): every
# [text](path) of README.md, docs/*.md, bench/*.md and bench/notes/*.md names a
# file that exists, and a #fragment a heading of the page it names.
add_test(NAME docs_links
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/doc_links.sh ${CMAKE_SOURCE_DIR})
set_tests_properties(docs_links PROPERTIES LABELS docs)
