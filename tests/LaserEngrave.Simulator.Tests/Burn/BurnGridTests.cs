using LaserEngrave.Simulator.Burn;

namespace LaserEngrave.Simulator.Tests.Burn;

public class BurnGridTests
{
    private static readonly BurnGrid Grid = new(1000.3, 2000.7, 559.93, 180, 90);

    [Fact]
    public void ColumnEdge_IsRoundedOnceFromTheUnroundedPitch()
    {
        // 1000.3 + 179 x 559.93 = 101227.77; adding a rounded pitch (560) 179 times would land 12 microsteps off.
        Assert.Equal(101_228, Grid.ColumnEdge(179));
        Assert.Equal(1000, Grid.ColumnEdge(0));
    }

    [Fact]
    public void RowAt_EveryRowLine_FindsItsRow()
    {
        for (var row = 0; row < Grid.HeightPx; row++)
        {
            Assert.Equal(row, Grid.RowAt(Grid.RowLine(row)));
        }
    }

    [Fact]
    public void RowAt_BetweenLinesOrOutside_IsMinusOne()
    {
        Assert.Equal(-1, Grid.RowAt(Grid.RowLine(3) + 1));
        Assert.Equal(-1, Grid.RowAt(0));
        Assert.Equal(-1, Grid.RowAt(Grid.RowLine(89) + 560));
    }

    [Fact]
    public void ColumnAt_EdgesBelongToTheColumnOnTheirRight()
    {
        for (var column = 0; column < Grid.WidthPx; column++)
        {
            Assert.Equal(column, Grid.ColumnAt(Grid.ColumnEdge(column)));
            Assert.Equal(column, Grid.ColumnAt(Grid.ColumnEdge(column + 1) - 0.001));
        }

        Assert.Equal(-1, Grid.ColumnAt(Grid.ColumnEdge(0) - 0.5));
        Assert.Equal(Grid.WidthPx, Grid.ColumnAt(Grid.ColumnEdge(Grid.WidthPx)));
    }

    [Fact]
    public void RowEdge_IsRoundedOnceFromTheUnroundedPitch()
    {
        // 2000.7 + 89 x 559.93 = 51834.47.
        Assert.Equal(51_834, Grid.RowEdge(89));
        Assert.Equal(2001, Grid.RowEdge(0));
    }

    [Fact]
    public void RowCellAt_RowLinesAndEdges_FallInTheirCells()
    {
        for (var row = 0; row < Grid.HeightPx; row++)
        {
            Assert.Equal(row, Grid.RowCellAt(Grid.RowLine(row)));
            Assert.Equal(row, Grid.RowCellAt(Grid.RowEdge(row)));
            Assert.Equal(row, Grid.RowCellAt(Grid.RowEdge(row + 1) - 0.001));
        }

        Assert.Equal(-1, Grid.RowCellAt(2000.9));
        Assert.Equal(Grid.HeightPx, Grid.RowCellAt(Grid.RowEdge(Grid.HeightPx)));
    }

    [Fact]
    public void Round_HalfMicrostep_GoesAwayFromZero()
    {
        Assert.Equal(3, BurnGrid.Round(2.5));
        Assert.Equal(2, BurnGrid.Round(2.4999));
    }

    [Fact]
    public void Constructor_PitchUnderOneMicrostep_Throws()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new BurnGrid(0, 0, 0.5, 10, 10));
    }
}
