// Cross-check with VTK itself: a .vtu written by Sinew is opened by VTK's XML reader
// (tests/vtk_reader_check.py, Debian's python3-vtk9). Skipped when python3 has no vtk.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/wait.h>

#include "io_test_support.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

constexpr const char* kPython = "/usr/bin/python3";

int exit_status(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

bool python_has_vtk() {
  const std::string command = std::string(kPython) + " -c \"import vtk\" > /dev/null 2>&1";
  return exit_status(std::system(command.c_str())) == 0;
}

// Runs the checker; returns its exit status.
int vtk_check(const std::filesystem::path& file, Eigen::Index points, Eigen::Index cells, const std::string& arrays) {
  const auto script = test::data_path("..") / "vtk_reader_check.py";
  const std::string command = std::string(kPython) + " '" + script.string() + "' '" + file.string() +
                              "' --points " + std::to_string(points) + " --cells " + std::to_string(cells) +
                              " --arrays " + arrays;
  return exit_status(std::system(command.c_str()));
}

TEST(IoVtkReaderCheck, VtkReadsOurVtuWithAllArrays) {
  if (!python_has_vtk()) GTEST_SKIP() << kPython << " cannot import vtk (Debian package python3-vtk9)";
  test::TempDir dir;
  for (const bool tets : {false, true}) {
    VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 1), Eigen::Vector3i(4, 2, 3));
    if (tets) mesh = tetrahedralize_hexes(mesh);
    Eigen::VectorXd x = mesh.rest_positions() * 1.1;
    VtuFields fields;
    fields.point_vectors.emplace_back("velocity", Eigen::VectorXd::Ones(x.size()));
    for (const char* name : {"J", "energy_density", "stress_norm", "energy"}) {
      fields.cell_scalars.emplace_back(name, Eigen::VectorXd::LinSpaced(mesh.num_elements(), 0.5, 1.5));
    }
    const auto path = dir / (tets ? "tets.vtu" : "hexes.vtu");
    write_vtu(path, mesh, x, fields);
    const Eigen::Index np = mesh.num_vertices(), nc = mesh.num_elements();
    EXPECT_EQ(vtk_check(path, np, nc, "displacement velocity J energy_density stress_norm energy --positive-volumes"), 0);
    // The checker itself must fail on wrong expectations, or the line above proves nothing.
    EXPECT_EQ(vtk_check(path, np + 1, nc, "displacement"), 1);
    EXPECT_EQ(vtk_check(path, np, nc, "no_such_array"), 1);
    VolumeMesh mirrored = mesh;  // odd node permutation: every element inverted for VTK
    mirrored.elements.col(1).swap(mirrored.elements.col(tets ? 2 : 3));
    if (!tets) mirrored.elements.col(5).swap(mirrored.elements.col(7));
    write_vtu(dir / "mirrored.vtu", mirrored, x);
    EXPECT_EQ(vtk_check(dir / "mirrored.vtu", np, nc, "displacement --positive-volumes"), 1);
  }
}

TEST(IoVtkReaderCheck, VtkReadsOurPvd) {
  if (!python_has_vtk()) GTEST_SKIP() << kPython << " cannot import vtk (Debian package python3-vtk9)";
  test::TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(1, 1, 1));
  std::filesystem::create_directory(dir / "frames");
  write_vtu(dir / "frames" / "f0.vtu", mesh, mesh.rest_positions());
  write_vtu(dir / "frames" / "f1.vtu", mesh, mesh.rest_positions() * 2.0);
  write_pvd(dir / "run.pvd", {{0.0, "frames/f0.vtu"}, {0.5, "frames/f1.vtu"}});
  // vtkPVDReader lives in ParaView, not VTK; check the collection with VTK's XML parser and
  // open each referenced file with the unstructured-grid reader.
  const std::string command = std::string(kPython) + " -c \"" +
                              "import sys, os, vtk\n"
                              "p = vtk.vtkXMLDataParser(); p.SetFileName(sys.argv[1]); assert p.Parse() == 1\n"
                              "c = p.GetRootElement().FindNestedElementWithName('Collection')\n"
                              "times = []\n"
                              "for i in range(c.GetNumberOfNestedElements()):\n"
                              "  d = c.GetNestedElement(i); times.append(float(d.GetAttribute('timestep')))\n"
                              "  r = vtk.vtkXMLUnstructuredGridReader()\n"
                              "  r.SetFileName(os.path.join(os.path.dirname(sys.argv[1]), d.GetAttribute('file'))); r.Update()\n"
                              "  assert r.GetOutput().GetNumberOfCells() == 1\n"
                              "assert times == [0.0, 0.5], times\n"
                              "\" '" + (dir / "run.pvd").string() + "'";
  EXPECT_EQ(exit_status(std::system(command.c_str())), 0);
}

}  // namespace
}  // namespace sinew
