#include "phase_names.h"

const char* phaseName(int phase) {
  static const char* const kNames[vpPhase_Count] = {"rigid",     "corotate", "assemble", "contacts",
                                                    "solve",     "embed",    "advect",   "forces",
                                                    "fractions", "pressure", "surface",  "viscosity",
                                                    "coupling"};
  return phase >= 0 && phase < vpPhase_Count ? kNames[phase] : "?";
}
