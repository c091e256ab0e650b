"""Processing algorithm terratin:pointstotin: a point layer, or a LAS or delimited text file, to
an exactly Delaunay TIN."""

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterCrs,
    QgsProcessingParameterField,
    QgsProcessingParameterFile,
    QgsProcessingParameterString,
    QgsProcessingParameterVectorLayer,
    QgsProcessing,
)

from .layer_files import layer_file
from .terratin_algorithm import TerratinAlgorithm, crs_text, given


class PointsToTin(TerratinAlgorithm):
    POINTS = "POINTS"
    POINTS_FILE = "POINTS_FILE"
    Z_FIELD = "Z_FIELD"
    CLASSES = "CLASSES"
    COLUMNS = "COLUMNS"
    SOURCE_CRS = "SOURCE_CRS"

    def name(self):
        return "pointstotin"

    def displayName(self):  # noqa: N802 (QGIS's name)
        return "Points to TIN"

    def shortHelpString(self):  # noqa: N802 (QGIS's name)
        return (
            "Triangulates points into an exactly Delaunay TIN, one polygon per triangle with "
            "terrain attributes. The points come from a point layer (z from the geometry or "
            "from a field) or from a file: LAS 1.0 to 1.4, LAZ (COPC too), or delimited text "
            "(x y z columns). Points at the same x, y are merged."
        )

    def createInstance(self):  # noqa: N802 (QGIS's name)
        return PointsToTin()

    def initAlgorithm(self, config=None):  # noqa: N802 (QGIS's name)
        self.addParameter(
            QgsProcessingParameterVectorLayer(
                self.POINTS, "Point layer", [QgsProcessing.TypeVectorPoint], optional=True
            )
        )
        self.addParameter(
            QgsProcessingParameterField(
                self.Z_FIELD, "Elevation field (empty: the geometry's z)",
                parentLayerParameterName=self.POINTS,
                type=QgsProcessingParameterField.Numeric, optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterFile(
                self.POINTS_FILE, "Or a point file (LAS 1.0-1.4, LAZ, delimited text)",
                fileFilter="Point files (*.las *.laz *.txt *.csv *.xyz);;All files (*)",
                optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterString(
                self.CLASSES, "LAS classes to keep (e.g. 2 for ground; empty: all)",
                optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterString(
                self.COLUMNS, "Text columns of x, y, z, from 1 (e.g. 1,2,3; empty: found)",
                optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterCrs(
                self.SOURCE_CRS, "CRS of the points (when the file has none)", optional=True
            )
        )
        self.addTinParameters()

    def inputOptions(self, parameters, context, feedback):  # noqa: N802
        layer = self.parameterAsVectorLayer(parameters, self.POINTS, context)
        file = self.parameterAsFile(parameters, self.POINTS_FILE, context)
        if (layer is None) == (not file):
            raise QgsProcessingException(
                "Points to TIN: give either a point layer or a point file, not both"
                if layer is not None
                else "Points to TIN: give a point layer or a point file"
            )
        options = {}
        if layer is not None:
            path, layer_name = layer_file(layer, context, feedback, "points")
            inputs = [path]
            if layer_name:
                options["input_layer"] = layer_name
            z_field = self.parameterAsString(parameters, self.Z_FIELD, context)
            if z_field:
                options["z_field"] = z_field
        else:
            inputs = [file]
        if given(parameters, self.CLASSES):
            options["classes"] = self.parameterAsString(parameters, self.CLASSES, context)
        if given(parameters, self.COLUMNS):
            options["columns"] = self.parameterAsString(parameters, self.COLUMNS, context)
        source_crs = self.parameterAsCrs(parameters, self.SOURCE_CRS, context)
        if source_crs.isValid():
            options["s_srs"] = crs_text(source_crs)
        return inputs, options
