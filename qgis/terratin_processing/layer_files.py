"""Vector layers as the files terratin reads."""

import os

from qgis.core import (
    QgsProcessingException,
    QgsProcessingUtils,
    QgsProviderRegistry,
    QgsVectorFileWriter,
)


def layer_file(layer, context, feedback, what):
    """(file, layer name or None) terratin reads `layer` from. A layer OGR reads whole from a
    file is read there; any other (a scratch layer, delimited text, a database, a filtered
    layer) is first saved to a GeoPackage in Processing's temporary folder, as layer `what`."""
    if layer.providerType() == "ogr":
        parts = QgsProviderRegistry.instance().decodeUri("ogr", layer.source())
        path = parts.get("path", "")
        if os.path.isfile(path) and not parts.get("subset"):
            return path, parts.get("layerName") or None
    path = os.path.join(QgsProcessingUtils.tempFolder(), f"terratin_{what}_{id(layer)}.gpkg")
    feedback.pushInfo(f"Saving '{layer.name()}' to {path} for terratin")
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = "GPKG"
    options.layerName = what
    error = QgsVectorFileWriter.writeAsVectorFormatV3(
        layer, path, context.transformContext(), options
    )
    if error[0] != QgsVectorFileWriter.NoError:
        raise QgsProcessingException(f"terratin: cannot save '{layer.name()}': {error[1]}")
    return path, what


def layer_source(layer, context, feedback, what):
    """`layer` as one source text terratin takes: FILE or FILE|layername=NAME."""
    path, name = layer_file(layer, context, feedback, what)
    return f"{path}|layername={name}" if name else path
