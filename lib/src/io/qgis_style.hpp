#pragma once
/// @file
/// QGIS layer style (.qml) that makes a TIN look like terrain: the triangles filled by their
/// z_mean on a hypsometric ramp (green lowlands, tan, brown, grey rock, white summits), in
/// equal-interval classes between the lowest and highest vertex, without outlines (at a
/// million triangles outlines would hide the fill). QGIS loads "<data set>.qml" beside a
/// file as the layer's default style.

#include <string>

namespace terratin::io::detail {

/// Classes of the graduated renderer: enough for a smooth ramp, few enough for a legend.
inline constexpr int kQgisStyleClasses = 16;

/// The .qml document colouring `attribute` from zMin to zMax (zMin < zMax; for zMin == zMax
/// one class is written). Pure: no file access.
std::string qgisTerrainStyle(const std::string& attribute, double zMin, double zMax);

} // namespace terratin::io::detail
