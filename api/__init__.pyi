"""Types of the public API (``import embroact``), for type checkers; the one list of its names.

The package loads these names on first use (lazy_loader.attach_stub reads this file at
import), so what a type checker sees and what ``import embroact`` provides are the same list.
"""
from .export.files.designfile import (
    load_design as load_design,
    save_design as save_design,
    loads_design as loads_design,
    dumps_design as dumps_design,
)
from .export.files.svgfile import svg_centerline as svg_centerline, read_svg_path as read_svg_path
from .patterns.design import (
    Design as Design,
    ActuatorSpec as ActuatorSpec,
    MachineSettings as MachineSettings,
    OperationSettings as OperationSettings,
    ModelSettings as ModelSettings,
    default_design as default_design,
    design_from_dict as design_from_dict,
    design_to_dict as design_to_dict,
    build_plan as build_plan,
)
from .patterns.centerline import Centerline as Centerline
from .patterns.params import (
    Tube as Tube,
    ZigzagParams as ZigzagParams,
    CrossParams as CrossParams,
    StitchOptions as StitchOptions,
)
from .patterns.plan import StitchPlan as StitchPlan, Command as Command, Role as Role
from .patterns.zigzag import zigzag as zigzag
from .patterns.cross import cross as cross
from .predict.analysis import (
    analyse as analyse,
    DesignAnalysis as DesignAnalysis,
    ActuatorAnalysis as ActuatorAnalysis,
)
from .predict.curve import curve as curve, ActuatorModel as ActuatorModel, Curve as Curve
from .predict.rules import check_design as check_design
from .export.machine.formats import write as write, WriteResult as WriteResult
from .export.report.build import build as build, BuildResult as BuildResult
from .patterns.base.errors import (
    EmbroactError as EmbroactError,
    ParameterError as ParameterError,
    PatternError as PatternError,
    PathError as PathError,
    DesignFileError as DesignFileError,
    ModelDomainError as ModelDomainError,
    SolverError as SolverError,
    ExportError as ExportError,
)

__version__: str
__all__ = [
    "load_design",
    "save_design",
    "loads_design",
    "dumps_design",
    "svg_centerline",
    "read_svg_path",
    "Design",
    "ActuatorSpec",
    "MachineSettings",
    "OperationSettings",
    "ModelSettings",
    "default_design",
    "design_from_dict",
    "design_to_dict",
    "build_plan",
    "Centerline",
    "Tube",
    "ZigzagParams",
    "CrossParams",
    "StitchOptions",
    "StitchPlan",
    "Command",
    "Role",
    "zigzag",
    "cross",
    "analyse",
    "DesignAnalysis",
    "ActuatorAnalysis",
    "curve",
    "ActuatorModel",
    "Curve",
    "check_design",
    "write",
    "WriteResult",
    "build",
    "BuildResult",
    "EmbroactError",
    "ParameterError",
    "PatternError",
    "PathError",
    "DesignFileError",
    "ModelDomainError",
    "SolverError",
    "ExportError",
    "__version__",
]
