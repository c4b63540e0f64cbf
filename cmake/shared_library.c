/* The shared library's own translation unit (cmake/Library.cmake): the
 * library is the public API's objects, taken whole from tr_api, and what
 * they need of the layers; a library target needs one source of its own. */
typedef int tr_shared_library_unit;
