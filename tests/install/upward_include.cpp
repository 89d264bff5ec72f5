// Built by the Layers.* CTest tests as a target linking one layer: an include of a
// layer above must not be found (LAYER_INCLUDE names it), and one below must be.
#include LAYER_INCLUDE
int main() {
  return 0;
}
