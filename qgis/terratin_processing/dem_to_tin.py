"""Processing algorithm terratin:demtotin: a DEM raster layer to a TIN, whole or simplified."""

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterBand,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
)

from .terratin_algorithm import TerratinAlgorithm, given


class DemToTin(TerratinAlgorithm):
    INPUT = "INPUT"
    BAND = "BAND"
    MAX_ERROR = "MAX_ERROR"
    MAX_POINTS = "MAX_POINTS"
    FILL_HOLES = "FILL_HOLES"
    MEMORY_LIMIT = "MEMORY_LIMIT"

    def name(self):
        return "demtotin"

    def displayName(self):  # noqa: N802 (QGIS's name)
        return "DEM to TIN"

    def shortHelpString(self):  # noqa: N802 (QGIS's name)
        return (
            "Triangulates the cell centres of a DEM into an exactly Delaunay TIN, one polygon "
            "per triangle with terrain attributes. With a maximum error or a maximum number of "
            "points the TIN is simplified: every valid cell stays within the maximum error (z "
            "units) of it. Nodata cells are left out. The DEM must be a file GDAL reads. With a "
            "memory limit (advanced) the DEM is read and triangulated tile by tile and the TIN "
            "written as the tiles are done, for DEMs larger than memory: one TIN without "
            "cracks, exactly Delaunay within each tile."
        )

    def createInstance(self):  # noqa: N802 (QGIS's name)
        return DemToTin()

    def initAlgorithm(self, config=None):  # noqa: N802 (QGIS's name)
        self.addParameter(QgsProcessingParameterRasterLayer(self.INPUT, "DEM"))
        # Optional, so that a script leaving it out gets the default (QGIS 3.22 checks a
        # missing mandatory band before applying its default).
        self.addParameter(
            QgsProcessingParameterBand(
                self.BAND, "Band", defaultValue=1, parentLayerParameterName=self.INPUT,
                optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterNumber(
                self.MAX_ERROR, "Maximum error (z units; empty: every cell a vertex)",
                QgsProcessingParameterNumber.Double, optional=True, minValue=0.0,
            )
        )
        self.addParameter(
            QgsProcessingParameterNumber(
                self.MAX_POINTS, "Maximum number of points (empty: no limit)",
                QgsProcessingParameterNumber.Integer, optional=True, minValue=3,
            )
        )
        self.addParameter(
            QgsProcessingParameterBoolean(
                self.FILL_HOLES, "Cover nodata holes with triangles (simplified TINs)",
                defaultValue=False,
            )
        )
        limit = QgsProcessingParameterNumber(
            self.MEMORY_LIMIT,
            "Memory limit (MiB; empty: the DEM and the TIN held whole)",
            QgsProcessingParameterNumber.Integer, optional=True, minValue=1,
        )
        limit.setFlags(limit.flags() | limit.FlagAdvanced)
        self.addParameter(limit)
        self.addTinParameters()

    def inputOptions(self, parameters, context, feedback):  # noqa: N802
        layer = self.parameterAsRasterLayer(parameters, self.INPUT, context)
        if layer is None:
            raise QgsProcessingException("DEM to TIN: no DEM layer")
        if layer.providerType() != "gdal":
            raise QgsProcessingException(
                f"DEM to TIN: '{layer.name()}' is a {layer.providerType()} layer; terratin "
                "reads rasters through GDAL: save it as a GeoTIFF first"
            )
        options = {"band": self.parameterAsInt(parameters, self.BAND, context) or 1}
        if given(parameters, self.MAX_ERROR):
            options["max_error"] = self.parameterAsDouble(parameters, self.MAX_ERROR, context)
        if given(parameters, self.MAX_POINTS):
            options["max_points"] = self.parameterAsInt(parameters, self.MAX_POINTS, context)
        if self.parameterAsBoolean(parameters, self.FILL_HOLES, context):
            options["fill_holes"] = True
        if given(parameters, self.MEMORY_LIMIT):
            mebibytes = self.parameterAsInt(parameters, self.MEMORY_LIMIT, context)
            options["memory_limit"] = f"{mebibytes}M"
        return [layer.source()], options
