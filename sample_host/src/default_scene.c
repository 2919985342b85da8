#include "default_scene.h"

#include <stdio.h>

const char* defaultScenePath(void) {
  FILE* f = fopen(VP_SOURCE_DEFAULT_SCENE, "r");
  if (f) {
    fclose(f);
    return VP_SOURCE_DEFAULT_SCENE;
  }
  return VP_INSTALLED_DEFAULT_SCENE;
}
