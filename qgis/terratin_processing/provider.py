"""The Processing provider "terratin": its algorithms and the outputs they can write."""

from qgis.core import QgsProcessingProvider

from .dem_to_tin import DemToTin
from .points_to_tin import PointsToTin


class TerratinProvider(QgsProcessingProvider):
    def id(self):
        return "terratin"

    def name(self):
        return "terratin"

    def longName(self):  # noqa: N802 (QGIS's name)
        try:
            import terratin

            return f"terratin {terratin.__version__}"
        except ImportError:
            return "terratin (its Python module is not installed)"

    def loadAlgorithms(self):  # noqa: N802 (QGIS's name)
        for algorithm in (DemToTin(), PointsToTin()):
            self.addAlgorithm(algorithm)

    # terratin writes files itself, in the formats its writers know; Processing then offers
    # only these (no memory layers: a TIN of millions of triangles belongs in a file).
    def supportsNonFileBasedOutput(self):  # noqa: N802 (QGIS's name)
        return False

    def supportedOutputVectorLayerExtensions(self):  # noqa: N802 (QGIS's name)
        return ["gpkg", "shp", "fgb"]

    def defaultVectorFileExtension(self, has_geometry=True):  # noqa: N802 (QGIS's name)
        return "gpkg"
