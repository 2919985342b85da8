/* Short lower-case names of the step phases (vpPhase), for the HUD and the stats CSV. */
#ifndef VP_SAMPLE_PHASE_NAMES_H
#define VP_SAMPLE_PHASE_NAMES_H

#include "volphys/volphys.h"

/* "?" for a phase this host does not know. */
const char* phaseName(int phase);

#endif
