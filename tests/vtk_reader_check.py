#!/usr/bin/python3
"""Opens a .vtu with VTK's own XML reader and checks its size and arrays.

usage: vtk_reader_check.py FILE --points N --cells M [--arrays NAME ...] [--positive-volumes]
Exits 0 when VTK reads the file without errors, it has N points and M cells, every named
array exists as point or cell data (with one value per point or cell) and, with
--positive-volumes, VTK's signed cell volumes (vtkMeshQuality) are all positive, i.e. VTK
sees the node order as uninverted; 1 otherwise; 77 when the vtk module is missing.
"""
import argparse
import sys

try:
    import vtk
except ImportError:
    print("vtk_reader_check: python3 'vtk' module is not available", file=sys.stderr)
    sys.exit(77)


class ErrorObserver:
    def __init__(self):
        self.messages = []

    def __call__(self, caller, event):
        self.messages.append(event)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("file")
    parser.add_argument("--points", type=int, required=True)
    parser.add_argument("--cells", type=int, required=True)
    parser.add_argument("--arrays", nargs="*", default=[])
    parser.add_argument("--positive-volumes", action="store_true")
    args = parser.parse_args()

    reader = vtk.vtkXMLUnstructuredGridReader()
    observer = ErrorObserver()
    reader.AddObserver("ErrorEvent", observer)
    reader.AddObserver("WarningEvent", observer)
    reader.GetExecutive().AddObserver("ErrorEvent", observer)
    if not reader.CanReadFile(args.file):
        print(f"vtk_reader_check: VTK cannot read {args.file}", file=sys.stderr)
        return 1
    reader.SetFileName(args.file)
    reader.Update()
    problems = [f"VTK reported {e}" for e in observer.messages]
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() != args.points:
        problems.append(f"{grid.GetNumberOfPoints()} points, expected {args.points}")
    if grid.GetNumberOfCells() != args.cells:
        problems.append(f"{grid.GetNumberOfCells()} cells, expected {args.cells}")
    for name in args.arrays:
        point_array = grid.GetPointData().GetArray(name)
        cell_array = grid.GetCellData().GetArray(name)
        if point_array is not None:
            if point_array.GetNumberOfTuples() != args.points:
                problems.append(f"point array '{name}' has {point_array.GetNumberOfTuples()} tuples")
        elif cell_array is not None:
            if cell_array.GetNumberOfTuples() != args.cells:
                problems.append(f"cell array '{name}' has {cell_array.GetNumberOfTuples()} tuples")
        else:
            problems.append(f"no point or cell array named '{name}'")
    if args.positive_volumes:
        quality = vtk.vtkMeshQuality()
        quality.SetInputData(grid)
        quality.SetHexQualityMeasureToVolume()
        quality.SetTetQualityMeasureToVolume()
        quality.Update()
        volumes = quality.GetOutput().GetCellData().GetArray("Quality")
        bad = [i for i in range(volumes.GetNumberOfTuples()) if not volumes.GetValue(i) > 0]
        if bad:
            problems.append(f"{len(bad)} cells with non-positive volume, first {bad[0]}: {volumes.GetValue(bad[0])}")
    for p in problems:
        print(f"vtk_reader_check: {args.file}: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
