"""What terratin's Processing algorithms share: the triangulation and output parameters, and
the run of terratin.build with progress and cancellation wired to QgsProcessingFeedback."""

import os

from qgis.core import (
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterField,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterVectorDestination,
    QgsProcessingParameterVectorLayer,
    QgsProcessingUtils,
)

from .layer_files import layer_source
from .terrain_style import apply_terrain_style_on_load

# The choices as terratin names them; the first is the default.
METHODS = ["auto", "strips", "sequential", "batch", "circumcircle"]
ATTRIBUTE_SETS = ["all", "basic", "none"]
# The formats terratin writes that Processing loads as a vector layer (terratin's mesh formats,
# 2dm ply obj landxml, would come back as a file QGIS opens as no polygon layer); the PLY mesh
# is the MESH output's.
VECTOR_EXTENSIONS = ["gpkg", "shp", "fgb"]


class TerratinAlgorithm(QgsProcessingAlgorithm):
    """A Processing algorithm that runs terratin.build on files and writes a TIN layer."""

    METHOD = "METHOD"
    THREADS = "THREADS"
    ATTRIBUTES = "ATTRIBUTES"
    TERRAIN_STYLE = "TERRAIN_STYLE"
    TARGET_CRS = "TARGET_CRS"
    BREAKLINES = "BREAKLINES"
    CLIP = "CLIP"
    ERASE = "ERASE"
    REPLACE = "REPLACE"
    REPLACE_Z_FIELD = "REPLACE_Z_FIELD"
    OUTPUT = "OUTPUT"
    MESH = "MESH"
    VERTICES = "VERTICES"
    TRIANGLES = "TRIANGLES"

    def group(self):
        return "TIN"

    def groupId(self):  # noqa: N802 (QGIS's name)
        return "tin"

    def flags(self):
        # terratin releases the GIL and runs on its own threads: the task may run in the
        # background; cancelling is seen at the next progress report.
        return super().flags() | QgsProcessingAlgorithm.FlagCanCancel

    def addTinParameters(self):  # noqa: N802 (the QGIS API's case)
        """The parameters after the inputs: how to triangulate, and the output."""
        self.addParameter(
            QgsProcessingParameterMultipleLayers(
                self.BREAKLINES,
                "Breaklines (line layers: every segment becomes TIN edges)",
                QgsProcessing.TypeVectorLine, optional=True,
            )
        )
        for name, description in (
            (self.CLIP, "Clip area (polygons: triangles outside are removed)"),
            (self.ERASE, "Erase areas (polygons cut out as holes)"),
            (self.REPLACE, "Replace areas (lakes: polygons flattened to one level)"),
        ):
            self.addParameter(
                QgsProcessingParameterVectorLayer(
                    name, description, [QgsProcessing.TypeVectorPolygon], optional=True
                )
            )
        self.addParameter(
            QgsProcessingParameterField(
                self.REPLACE_Z_FIELD,
                "Level field of the replace areas (default: the lowest level of each shore)",
                parentLayerParameterName=self.REPLACE,
                type=QgsProcessingParameterField.Numeric, optional=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterCrs(
                self.TARGET_CRS, "Output CRS (default: the input's; geographic: its UTM zone)",
                optional=True,
            )
        )
        method = QgsProcessingParameterEnum(
            self.METHOD, "Triangulation method", options=METHODS, defaultValue=0
        )
        method.setFlags(method.flags() | method.FlagAdvanced)
        self.addParameter(method)
        self.addParameter(
            QgsProcessingParameterNumber(
                self.THREADS, "Threads (0: all)", QgsProcessingParameterNumber.Integer,
                defaultValue=0, minValue=0,
            )
        )
        self.addParameter(
            QgsProcessingParameterEnum(
                self.ATTRIBUTES, "Triangle attributes (basic: z, slope, aspect, area)",
                options=ATTRIBUTE_SETS, defaultValue=0,
            )
        )
        self.addParameter(
            QgsProcessingParameterBoolean(
                self.TERRAIN_STYLE, "Style the triangles by elevation (terrain colours)",
                defaultValue=True,
            )
        )
        self.addParameter(
            QgsProcessingParameterVectorDestination(
                self.OUTPUT, "TIN", type=QgsProcessing.TypeVectorPolygon
            )
        )
        self.addParameter(
            QgsProcessingParameterFileDestination(
                self.MESH, "TIN as a mesh layer (PLY, with its CRS)",
                fileFilter="PLY meshes (*.ply)", optional=True, createByDefault=False,
            )
        )
        self.addOutput(QgsProcessingOutputNumber(self.VERTICES, "Vertices"))
        self.addOutput(QgsProcessingOutputNumber(self.TRIANGLES, "Triangles"))

    def inputOptions(self, parameters, context, feedback):  # noqa: N802
        """(inputs, options) of terratin.build for this algorithm's input parameters."""
        raise NotImplementedError

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802 (QGIS's name)
        terratin = import_terratin()
        self.styledOutput = None
        # The output first: a refused one should cost no copy of a point layer.
        output = self.parameterAsOutputLayer(parameters, self.OUTPUT, context)
        check_vector_file(self.displayName(), output)
        inputs, options = self.inputOptions(parameters, context, feedback)
        options.update(self.tinOptions(parameters, context, feedback))
        try:
            report = terratin.build(
                inputs, output, progress=progress_of(feedback), overwrite=True, **options
            )
        except terratin.Cancelled:
            raise QgsProcessingException("terratin: cancelled") from None
        except terratin.Error as error:
            raise QgsProcessingException(f"terratin: {error}") from None
        for notice in report["notices"]:
            feedback.pushInfo(f"terratin: {notice}")
        counts = report["counts"]
        feedback.pushInfo(
            f"{counts['vertices']} vertices, {counts['triangles']} triangles "
            f"in {report['timings']['total']:.2f} s ({report['crs']['name']})"
        )
        self.styledOutput = output if options["qgis_style"] else None
        results = {
            self.OUTPUT: output,
            self.VERTICES: counts["vertices"],
            self.TRIANGLES: counts["triangles"],
        }
        mesh = self.parameterAsFileOutput(parameters, self.MESH, context)
        if mesh:
            results[self.MESH] = self.writeMesh(terratin, inputs, options, mesh, context, feedback)
        return results

    def writeMesh(self, terratin, inputs, options, mesh, context, feedback):  # noqa: N802
        """The same TIN as a PLY mesh (terratin builds it again: one build writes one file),
        loaded as a QGIS mesh layer when the algorithm ends."""
        if os.path.splitext(mesh)[1].lower() != ".ply":
            raise QgsProcessingException(
                f"{self.displayName()}: the mesh output is a PLY file (.ply), not '{mesh}'"
            )
        mesh_options = {k: v for k, v in options.items() if k not in ("attributes", "qgis_style")}
        try:
            terratin.build(
                inputs, mesh, progress=progress_of(feedback), overwrite=True, **mesh_options
            )
        except terratin.Cancelled:
            raise QgsProcessingException("terratin: cancelled") from None
        except terratin.Error as error:
            raise QgsProcessingException(f"terratin: {error}") from None
        context.addLayerToLoadOnCompletion(
            mesh,
            QgsProcessingContext.LayerDetails(
                "TIN mesh", context.project(), self.MESH, QgsProcessingUtils.LayerHint.Mesh
            ),
        )
        return mesh

    def postProcessAlgorithm(self, context, feedback):  # noqa: N802 (QGIS's name)
        # Here, in the main thread, after the run: the layer details belong to the context.
        if self.styledOutput:
            apply_terrain_style_on_load(self.styledOutput, context)
        return {}

    def tinOptions(self, parameters, context, feedback):  # noqa: N802
        """terratin.build's options of the shared parameters."""
        attributes = ATTRIBUTE_SETS[self.parameterAsEnum(parameters, self.ATTRIBUTES, context)]
        style = self.parameterAsBoolean(parameters, self.TERRAIN_STYLE, context)
        if style and attributes == "none":
            # The style colours by z_mean, one of the attributes.
            feedback.pushWarning("No terrain style: it needs the triangle attributes")
            style = False
        options = {
            "method": METHODS[self.parameterAsEnum(parameters, self.METHOD, context)],
            "threads": self.parameterAsInt(parameters, self.THREADS, context),
            "attributes": attributes,
            "qgis_style": style,
        }
        breaklines = self.parameterAsLayerList(parameters, self.BREAKLINES, context)
        if breaklines:
            options["breaklines"] = [
                layer_source(layer, context, feedback, "breaklines") for layer in breaklines
            ]
        for name, option in ((self.CLIP, "clip"), (self.ERASE, "erase"), (self.REPLACE, "replace")):
            layer = self.parameterAsVectorLayer(parameters, name, context)
            if layer is not None:
                options[option] = layer_source(layer, context, feedback, option)
        level_field = self.parameterAsString(parameters, self.REPLACE_Z_FIELD, context)
        if level_field:
            options["replace_z_field"] = level_field
        target = self.parameterAsCrs(parameters, self.TARGET_CRS, context)
        if target.isValid():
            options["t_srs"] = crs_text(target)
        return options


def import_terratin():
    """The terratin Python module, or a message that says how to install it."""
    try:
        import terratin
    except ImportError as error:
        raise QgsProcessingException(
            f"terratin's Python module cannot be imported ({error}): install it with "
            "terratin's build (cmake --install build/release --component python, or pip install .) "
            "or put its folder on "
            "PYTHONPATH; docs/qgis.md says how"
        ) from None
    return terratin


def check_vector_file(algorithm, output):
    """A QgsProcessingException unless `output` is a file path of a format terratin writes and
    Processing loads as a vector layer (a script may pass "memory:" or "x.ply")."""
    extension = os.path.splitext(output)[1].lstrip(".").lower()
    if extension not in VECTOR_EXTENSIONS:
        raise QgsProcessingException(
            f"{algorithm}: terratin writes the TIN to a file ending in "
            f"{', '.join('.' + e for e in VECTOR_EXTENSIONS)}, not to '{output}'"
        )


def progress_of(feedback):
    """terratin's progress callable for `feedback`: the bar and the phase's name, and False
    once cancelled."""
    shown = [None]

    def progress(fraction, message):
        feedback.setProgress(100.0 * fraction)
        if message and message != shown[0]:
            feedback.setProgressText(f"terratin: {message}")
            shown[0] = message
        return not feedback.isCanceled()

    return progress


def given(parameters, name):
    """Whether an optional parameter has a value (a dialog's empty field gives None or "")."""
    return parameters.get(name) not in (None, "")


def crs_text(crs):
    """A QgsCoordinateReferenceSystem as terratin's --s_srs / --t_srs take it."""
    return crs.authid() if crs.authid() else crs.toWkt()
