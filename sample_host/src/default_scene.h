/* The scene the sample programs open without --scene: the source tree's when it is there (a
 * build tree), else the one `cmake --install` put under the prefix's share/volphys/scenes. */
#ifndef VP_SAMPLE_DEFAULT_SCENE_H
#define VP_SAMPLE_DEFAULT_SCENE_H

const char* defaultScenePath(void);

#endif
