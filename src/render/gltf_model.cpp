#include "render/gltf_model.hpp"
