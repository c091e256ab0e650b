#include "terratin/io/tile_index.hpp"

#include "atomic_output.hpp"
#include "ogr_dataset_support.hpp"

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <ogrsf_frmts.h>

#include <memory>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "TileIndex";

void addField(OGRLayer& layer, const char* name, OGRFieldType type,
              const std::filesystem::path& path) {
    OGRFieldDefn field(name, type);
    if (layer.CreateField(&field) != OGRERR_NONE)
        throwGdalError(kStage, std::string("cannot add the field ") + name + " to", path.string());
}

void addTile(OGRLayer& layer, const TileIndexEntry& entry, const std::filesystem::path& path) {
    OGRFeature feature(layer.GetLayerDefn());
    feature.SetField("file", entry.file.c_str());
    feature.SetField("tile_row", static_cast<GIntBig>(entry.tileRow));
    feature.SetField("tile_column", static_cast<GIntBig>(entry.tileColumn));
    feature.SetField("points", static_cast<GIntBig>(entry.points));
    feature.SetField("triangles", static_cast<GIntBig>(entry.triangles));
    auto ring = std::make_unique<OGRLinearRing>();
    for (const auto& [x, y] : entry.corners)
        ring->addPoint(x, y);
    ring->closeRings();
    OGRPolygon polygon;
    polygon.addRingDirectly(ring.release());
    feature.SetGeometry(&polygon);
    if (layer.CreateFeature(&feature) != OGRERR_NONE)
        throwGdalError(kStage, "cannot write a tile to", path.string());
}

} // namespace

void writeTileIndex(const std::filesystem::path& path, const std::string& crsWkt,
                    const std::vector<TileIndexEntry>& entries, bool overwrite) {
    initialiseGdal();
    detail::checkOutputLocation(kStage, path);
    detail::refuseExistingOutputs(kStage, {path}, overwrite);
    std::optional<OGRSpatialReference> crs = detail::parseOutputCrs(crsWkt);
    const detail::AtomicOutput output(kStage, path, detail::existingTargetFor(overwrite));
    const std::filesystem::path temporary = output.temporary(".gpkg");
    GDALDatasetUniquePtr dataset = detail::createDataset("GPKG", temporary, path);
    OGRLayer* layer = dataset->CreateLayer("tiles", crs ? &*crs : nullptr, wkbPolygon, nullptr);
    if (layer == nullptr)
        throwGdalError(kStage, "cannot create the layer tiles in", path.string());
    addField(*layer, "file", OFTString, path);
    for (const char* name : {"tile_row", "tile_column", "points", "triangles"})
        addField(*layer, name, OFTInteger64, path);
    if (layer->StartTransaction() != OGRERR_NONE)
        throwGdalError(kStage, "cannot start writing", path.string());
    for (const TileIndexEntry& entry : entries)
        addTile(*layer, entry, path);
    if (layer->CommitTransaction() != OGRERR_NONE)
        throwGdalError(kStage, "cannot finish writing", path.string());
    detail::closeDataset(dataset, path);
    output.commit(temporary, path);
}

} // namespace terratin::io
