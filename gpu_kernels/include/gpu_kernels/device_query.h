// Whether the CUDA path is compiled in and how many devices it can use right now. Works
// (answering 0) on machines without a GPU or driver.
#pragma once

namespace vp::gpu {

bool cudaCompiled();
int cudaDeviceCount();

}  // namespace vp::gpu
