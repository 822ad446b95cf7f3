#include "node/tiling.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace wsn::node {
namespace {

/// Begin of part `i` when `n` cells are split into `parts` near-equal ranges.
std::int32_t splitBegin(std::int32_t n, std::int32_t parts, std::int32_t i) {
  return static_cast<std::int32_t>(static_cast<std::int64_t>(i) * n / parts);
}

Tile makeTile(const common::SensorLayout& layout, int index, std::int32_t c0, std::int32_t c1, std::int32_t r0,
              std::int32_t r1) {
  const std::int32_t columns = layout.cellColumns();
  const common::Rect low = layout.cellRect(r0 * columns + c0);
  const common::Rect high = layout.cellRect((r1 - 1) * columns + (c1 - 1));
  return Tile{index, c0, c1, r0, r1, common::Rect{low.x_min, low.y_min, high.x_max, high.y_max}};
}

/// Tiles per column strip when `count` tiles go into `strips` strips (extra tiles go left).
std::int32_t tilesInStrip(std::int32_t count, std::int32_t strips, std::int32_t strip) {
  return count / strips + (strip < count % strips ? 1 : 0);
}

}  // namespace

std::vector<Tile> makeTiles(const common::SensorLayout& layout, int count) {
  const std::int32_t columns = layout.cellColumns();
  const std::int32_t rows = layout.cellRows();
  const std::int64_t cells = static_cast<std::int64_t>(columns) * rows;
  if (count < 1) throw std::invalid_argument("makeTiles: need at least one tile, got " + std::to_string(count));
  if (count > cells)
    throw std::invalid_argument("makeTiles: " + std::to_string(count) + " tiles but only " + std::to_string(cells) +
                                " sensor cells (" + std::to_string(columns) + " x " + std::to_string(rows) +
                                "): a tile would be empty");

  // Internal boundary length in cell sides is what the tiles exchange readings across, so it
  // is the cost to minimise; a tie (2 tiles on a square field) goes to more tile columns.
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  std::int64_t best_cost = kNone;
  std::int32_t best_tx = 0;
  for (std::int32_t tx = 1; tx <= count; ++tx) {
    if (count % tx != 0) continue;
    const std::int32_t ty = count / tx;
    if (tx > columns || ty > rows) continue;
    const std::int64_t cost = static_cast<std::int64_t>(tx - 1) * rows + static_cast<std::int64_t>(ty - 1) * columns;
    if (cost <= best_cost) {
      best_cost = cost;
      best_tx = tx;
    }
  }

  std::vector<Tile> tiles;
  tiles.reserve(static_cast<std::size_t>(count));
  if (best_cost != kNone) {
    const std::int32_t tx = best_tx;
    const std::int32_t ty = count / tx;
    for (std::int32_t j = 0; j < ty; ++j)
      for (std::int32_t i = 0; i < tx; ++i)
        tiles.push_back(makeTile(layout, static_cast<int>(tiles.size()), splitBegin(columns, tx, i),
                                 splitBegin(columns, tx, i + 1), splitBegin(rows, ty, j), splitBegin(rows, ty, j + 1)));
    return tiles;
  }

  // No regular grid fits (e.g. a prime count larger than both cell dimensions): column strips,
  // each cut into its own number of rows. strips = ceil(count / rows) always fits because
  // count <= columns * rows.
  for (std::int32_t strips = 1; strips <= std::min(columns, count); ++strips) {
    if ((count + strips - 1) / strips > rows) continue;
    std::int64_t cost = static_cast<std::int64_t>(strips - 1) * rows;
    for (std::int32_t s = 0; s < strips; ++s)
      cost += static_cast<std::int64_t>(tilesInStrip(count, strips, s) - 1) *
              (splitBegin(columns, strips, s + 1) - splitBegin(columns, strips, s));
    if (cost <= best_cost) {
      best_cost = cost;
      best_tx = strips;
    }
  }
  const std::int32_t strips = best_tx;
  for (std::int32_t s = 0; s < strips; ++s) {
    const std::int32_t n = tilesInStrip(count, strips, s);
    for (std::int32_t j = 0; j < n; ++j)
      tiles.push_back(makeTile(layout, static_cast<int>(tiles.size()), splitBegin(columns, strips, s),
                               splitBegin(columns, strips, s + 1), splitBegin(rows, n, j), splitBegin(rows, n, j + 1)));
  }
  return tiles;
}

int tileOfCell(std::span<const Tile> tiles, std::int32_t column, std::int32_t row) {
  for (const Tile& tile : tiles)
    if (tile.ownsCell(column, row)) return tile.index;
  return -1;
}

std::vector<common::SensorId> tileSensorIds(const common::SensorLayout& layout, const Tile& tile, const char* who) {
  if (tile.cell_col_begin < 0 || tile.cell_col_end > layout.cellColumns() || tile.cell_col_begin >= tile.cell_col_end ||
      tile.cell_row_begin < 0 || tile.cell_row_end > layout.cellRows() || tile.cell_row_begin >= tile.cell_row_end)
    throw std::invalid_argument(std::string(who) + ": tile " + std::to_string(tile.index) +
                                " is empty or outside the sensor cell grid");
  std::vector<common::SensorId> ids;
  for (std::int32_t c = tile.cell_col_begin; c < tile.cell_col_end; ++c)
    for (std::int32_t r = tile.cell_row_begin; r < tile.cell_row_end; ++r) {
      const auto& in_cell = layout.sensorsInCell(r * layout.cellColumns() + c);
      ids.insert(ids.end(), in_cell.begin(), in_cell.end());
    }
  std::sort(ids.begin(), ids.end());
  return ids;
}

bool nearSharedSide(const common::SensorLayout& layout, const Tile& tile, common::Vec2 p, double reach) {
  const common::Rect& b = tile.bounds;
  return (tile.cell_col_begin > 0 && p.x - b.x_min <= reach) ||
         (tile.cell_col_end < layout.cellColumns() && b.x_max - p.x <= reach) ||
         (tile.cell_row_begin > 0 && p.y - b.y_min <= reach) ||
         (tile.cell_row_end < layout.cellRows() && b.y_max - p.y <= reach);
}

int tileOfCell(std::span<const Tile> tiles, const common::SensorLayout& layout, std::int32_t cell) {
  return tileOfCell(tiles, cell % layout.cellColumns(), cell / layout.cellColumns());
}

}  // namespace wsn::node
