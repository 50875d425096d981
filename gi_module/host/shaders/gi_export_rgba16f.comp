#version 460
#extension GL_GOOGLE_include_directive : require
#define EXPORT_FORMAT rgba16f
#include "gi_export.glsl"
