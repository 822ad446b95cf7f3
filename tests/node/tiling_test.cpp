#include "node/tiling.hpp"

#include <catch2/catch.hpp>

#include <set>
#include <stdexcept>
#include <vector>

#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"

namespace {

using wsn::common::Scenario;
using wsn::common::SensorLayout;
using wsn::node::makeTiles;
using wsn::node::Tile;

Scenario fieldOf(double width, double height) {
  Scenario s;
  s.region = {0.0, 0.0, width, height};
  s.run.seed = 11;
  return s;
}

/// Number of distinct column ranges and row ranges: the shape of a regular tile grid.
std::pair<std::size_t, std::size_t> gridShape(const std::vector<Tile>& tiles) {
  std::set<std::pair<int, int>> columns;
  std::set<std::pair<int, int>> rows;
  for (const Tile& t : tiles) {
    columns.insert({t.cell_col_begin, t.cell_col_end});
    rows.insert({t.cell_row_begin, t.cell_row_end});
  }
  return {columns.size(), rows.size()};
}

void requirePartition(const SensorLayout& layout, const std::vector<Tile>& tiles, int count) {
  REQUIRE(static_cast<int>(tiles.size()) == count);
  for (int i = 0; i < count; ++i) {
    CHECK(tiles[static_cast<std::size_t>(i)].index == i);
    CHECK(tiles[static_cast<std::size_t>(i)].cellCount() > 0);
  }
  const std::int32_t cells = layout.cellColumns() * layout.cellRows();
  for (std::int32_t cell = 0; cell < cells; ++cell) {
    int owners = 0;
    for (const Tile& t : tiles) owners += t.ownsCell(layout, cell) ? 1 : 0;
    REQUIRE(owners == 1);
    const int owner = wsn::node::tileOfCell(tiles, layout, cell);
    REQUIRE(owner >= 0);
    CHECK(tiles[static_cast<std::size_t>(owner)].ownsCell(layout, cell));
  }
  // Every sensor, through its cell, belongs to exactly one tile.
  for (wsn::common::SensorId id = 0; id < layout.size(); id += 37) {
    int owners = 0;
    for (const Tile& t : tiles) owners += t.ownsCell(layout, layout.cellOf(layout.truePosition(id))) ? 1 : 0;
    REQUIRE(owners == 1);
  }
}

}  // namespace

TEST_CASE("makeTiles partitions every cell exactly once for 1 to 8 tiles", "[node][tiling]") {
  // Default field 100 x 100, Rs = 1.5: cells of side 3, ceil(100 / 3) = 34 per side. Also a
  // long thin field (100 x 10 cells), a small one (5 x 3 cells) and a single row (7 x 1).
  for (auto [w, h] : std::vector<std::pair<double, double>>{{100, 100}, {300, 30}, {15, 9}, {21, 3}}) {
    const SensorLayout layout(sensorFieldConfig(fieldOf(w, h)));
    for (int count = 1; count <= 8; ++count) {
      if (count > layout.cellColumns() * layout.cellRows()) continue;
      INFO("field " << w << " x " << h << ", " << count << " tiles");
      requirePartition(layout, makeTiles(layout, count), count);
    }
  }
}

TEST_CASE("makeTiles arranges a square field as a near-square grid of tiles", "[node][tiling]") {
  const SensorLayout layout(sensorFieldConfig(fieldOf(100, 100)));
  REQUIRE(layout.cellColumns() == 34);
  // Internal boundary in cell sides: tx x ty costs (tx - 1) 34 + (ty - 1) 34, minimal for the
  // most square factorisation; ties (2x1 vs 1x2) go to more tile columns.
  CHECK(gridShape(makeTiles(layout, 1)) == std::pair<std::size_t, std::size_t>{1, 1});
  CHECK(gridShape(makeTiles(layout, 2)) == std::pair<std::size_t, std::size_t>{2, 1});
  CHECK(gridShape(makeTiles(layout, 3)) == std::pair<std::size_t, std::size_t>{3, 1});
  CHECK(gridShape(makeTiles(layout, 4)) == std::pair<std::size_t, std::size_t>{2, 2});
  CHECK(gridShape(makeTiles(layout, 6)) == std::pair<std::size_t, std::size_t>{3, 2});
  CHECK(gridShape(makeTiles(layout, 8)) == std::pair<std::size_t, std::size_t>{4, 2});

  // 34 columns into 3: floor(i 34 / 3) = 0, 11, 22, 34 -> widths 11, 11, 12.
  const auto three = makeTiles(layout, 3);
  CHECK(three[0].cell_col_end - three[0].cell_col_begin == 11);
  CHECK(three[1].cell_col_end - three[1].cell_col_begin == 11);
  CHECK(three[2].cell_col_end - three[2].cell_col_begin == 12);

  // Tiles are indexed row-major over the tile grid; 2 x 2 splits at cell 17, i.e. x = y = 51.
  const auto four = makeTiles(layout, 4);
  CHECK(four[1].bounds.x_min == Approx(51.0).margin(1e-12));
  CHECK(four[1].bounds.y_min == Approx(0.0).margin(1e-12));
  CHECK(four[2].bounds.x_min == Approx(0.0).margin(1e-12));
  CHECK(four[2].bounds.y_min == Approx(51.0).margin(1e-12));
  // 34 cells of side 3 reach 102 > 100: bounds are the union of whole cells.
  CHECK(four[3].bounds.x_max == Approx(102.0).margin(1e-12));
}

TEST_CASE("makeTiles cuts a long field across its length", "[node][tiling]") {
  // 300 x 30 -> 100 x 10 cells. 4 tiles: 4x1 costs 3 * 10 = 30 cell sides of boundary, 2x2
  // costs 10 + 100 = 110, 1x4 costs 300.
  const SensorLayout layout(sensorFieldConfig(fieldOf(300, 30)));
  CHECK(gridShape(makeTiles(layout, 4)) == std::pair<std::size_t, std::size_t>{4, 1});
}

TEST_CASE("makeTiles falls back to column strips when no tile grid fits", "[node][tiling]") {
  // 6 x 6 -> 2 x 2 cells; 3 tiles fit neither 3x1 nor 1x3, so one column strip holds two tiles
  // and the other one.
  const SensorLayout layout(sensorFieldConfig(fieldOf(6, 6)));
  REQUIRE(layout.cellColumns() == 2);
  REQUIRE(layout.cellRows() == 2);
  const auto tiles = makeTiles(layout, 3);
  requirePartition(layout, tiles, 3);
  CHECK(tiles[0].cellCount() == 1);
  CHECK(tiles[1].cellCount() == 1);
  CHECK(tiles[2].cellCount() == 2);
}

TEST_CASE("makeTiles rejects more tiles than cells and fewer than one", "[node][tiling]") {
  const SensorLayout layout(sensorFieldConfig(fieldOf(6, 6)));  // 4 cells
  CHECK_NOTHROW(makeTiles(layout, 4));
  CHECK_THROWS_AS(makeTiles(layout, 5), std::invalid_argument);
  CHECK_THROWS_AS(makeTiles(layout, 0), std::invalid_argument);
  CHECK_THROWS_AS(makeTiles(layout, -3), std::invalid_argument);
}

TEST_CASE("tileOfCell returns -1 outside every tile", "[node][tiling]") {
  const SensorLayout layout(sensorFieldConfig(fieldOf(100, 100)));
  const auto tiles = makeTiles(layout, 4);
  CHECK(wsn::node::tileOfCell(tiles, 0, 0) == 0);
  CHECK(wsn::node::tileOfCell(tiles, 33, 33) == 3);
  CHECK(wsn::node::tileOfCell(tiles, 34, 0) == -1);
  CHECK(wsn::node::tileOfCell(tiles, -1, 0) == -1);
}
