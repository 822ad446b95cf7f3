// Splits the sensor field into rectangular tiles, one per node process. Tiles are unions of
// the fixed cells of common::SensorLayout, so every sensor belongs to exactly one tile.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/sensor_layout.hpp"

namespace wsn::node {

/// A rectangle of layout cells: columns [cell_col_begin, cell_col_end) x rows
/// [cell_row_begin, cell_row_end).
struct Tile {
  int index = 0;
  std::int32_t cell_col_begin = 0;
  std::int32_t cell_col_end = 0;
  std::int32_t cell_row_begin = 0;
  std::int32_t cell_row_end = 0;
  /// Union of the tile's cell rectangles (the last column/row of cells may reach past the region).
  common::Rect bounds;

  /// True when the cell at (column, row) of the layout's cell grid lies in this tile.
  bool ownsCell(std::int32_t column, std::int32_t row) const {
    return column >= cell_col_begin && column < cell_col_end && row >= cell_row_begin && row < cell_row_end;
  }
  /// True when layout cell `cell` (row-major index) lies in this tile.
  bool ownsCell(const common::SensorLayout& layout, std::int32_t cell) const {
    return ownsCell(cell % layout.cellColumns(), cell / layout.cellColumns());
  }
  /// Number of layout cells in the tile.
  std::int64_t cellCount() const {
    return static_cast<std::int64_t>(cell_col_end - cell_col_begin) * (cell_row_end - cell_row_begin);
  }
};

/// Splits the layout's cell grid into `count` non-empty rectangles, indexed row-major over the
/// tile grid. Among the grids tx x ty = count that fit the cell grid it takes the one with the
/// shortest internal boundary (least boundary exchange; ties: more tile columns), so a square
/// field gives 4 -> 2x2, 2 -> 2x1, 3 -> 3x1, 6 -> 3x2, 8 -> 4x2. Cells are split as evenly as
/// possible. When no such grid fits (e.g. 3 tiles on 2x2 cells) it falls back to column strips
/// holding ceil/floor(count / strips) tiles each. Throws std::invalid_argument when count < 1 or
/// count exceeds the number of cells (a tile would be empty).
std::vector<Tile> makeTiles(const common::SensorLayout& layout, int count);

/// The sensors of `tile`'s cells, sorted by id; throws std::invalid_argument ("`who`: tile N is
/// empty or outside the sensor cell grid") for a tile that does not lie in the layout's cell grid.
std::vector<common::SensorId> tileSensorIds(const common::SensorLayout& layout, const Tile& tile, const char* who);

/// True when p lies within `reach` of a side of `tile` that it shares with another tile (a side
/// not on the edge of the layout's cell grid): a sensor there may be heard across the edge.
bool nearSharedSide(const common::SensorLayout& layout, const Tile& tile, common::Vec2 p, double reach);

/// Index of the tile owning cell (column, row), or -1 when no tile does.
int tileOfCell(std::span<const Tile> tiles, std::int32_t column, std::int32_t row);

/// Index of the tile owning layout cell `cell` (row-major index), or -1 when no tile does.
int tileOfCell(std::span<const Tile> tiles, const common::SensorLayout& layout, std::int32_t cell);

}  // namespace wsn::node
