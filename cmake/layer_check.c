/* This file contains the empty program that each layer's link check links
 * the whole of one layer's library into (host/CMakeLists.txt tr_layer): a
 * call from a layer to one above it is then an undefined reference and the
 * build fails, instead of resolving quietly in the final executable. */
int main(void) { return 0; }
