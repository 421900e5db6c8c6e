using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Calibration;

public class AxisCalibrationTests
{
    [Fact]
    public void MachineMatrix_HalfDegreeAndScales_MatchesTheModel()
    {
        var calibration = new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500 };

        var (m11, m12, m22) = calibration.MachineMatrix();

        // Unit +Y commanded moves the sample 0.9995 along a direction 90.5° from +X.
        var g = 0.5 * Math.PI / 180;
        Assert.Equal(1.0005, m11, 15);
        Assert.Equal(0.9995 * Math.Cos(90.5 * Math.PI / 180), m12, 15);
        Assert.Equal(0.9995 * Math.Cos(g), m22, 15);
    }

    [Fact]
    public void FromMachineMatrix_OfMachineMatrix_GivesTheSameErrors()
    {
        var calibration = new AxisCalibration { SquarenessDegrees = -0.3, ScaleXPpm = 120, ScaleYPpm = 800 };
        var (m11, m12, m22) = calibration.MachineMatrix();

        var back = AxisCalibration.FromMachineMatrix(m11, m12, m22);

        Assert.Equal(-0.3, back.SquarenessDegrees, 12);
        Assert.Equal(120, back.ScaleXPpm, 7);
        Assert.Equal(800, back.ScaleYPpm, 7);
    }

    [Fact]
    public void ThenResidual_CompensatedPatternResidual_ComposesToTheMachine()
    {
        // The machine has M; a job compensated for C0 moves the sample by M C0⁻¹; the residual measured is that matrix.
        var machine = new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500 };
        var first = new AxisCalibration { SquarenessDegrees = 0.45, ScaleXPpm = 450, ScaleYPpm = -400 };
        var (m11, m12, m22) = machine.MachineMatrix();
        var (c11, c12, c22) = first.MachineMatrix();

        // Upper triangular inverse of C0, then M C0⁻¹, by hand.
        double i11 = 1 / c11, i12 = -c12 / (c11 * c22), i22 = 1 / c22;
        var residual = AxisCalibration.FromMachineMatrix(m11 * i11, (m11 * i12) + (m12 * i22), m22 * i22);

        var composed = first.ThenResidual(residual);

        Assert.Equal(0.5, composed.SquarenessDegrees, 10);
        Assert.Equal(500, composed.ScaleXPpm, 6);
        Assert.Equal(-500, composed.ScaleYPpm, 6);
    }

    [Fact]
    public void ToStage_ThenMachine_GivesTheWantedDisplacement()
    {
        var compensation = new StageCompensation(new AxisCalibration { SquarenessDegrees = 0.5, ScaleXPpm = 500, ScaleYPpm = -500 });

        var (sx, sy) = compensation.ToStage(3000, 7000);
        var (x, y) = compensation.ToTrue(sx, sy);

        Assert.Equal(3000, x, 9);
        Assert.Equal(7000, y, 9);

        // sy = 7000 / (0.9995 cos 0.5°); sx = (3000 + 7000 tan 0.5°) / 1.0005.
        var g = 0.5 * Math.PI / 180;
        Assert.Equal(7000 / (0.9995 * Math.Cos(g)), sy, 9);
        Assert.Equal((3000 + (7000 * Math.Tan(g))) / 1.0005, sx, 9);
    }

    [Theory]
    [InlineData(6.0, 0.0, 0.0)]
    [InlineData(0.0, 200_000.0, 0.0)]
    [InlineData(0.0, 0.0, double.NaN)]
    public void Validate_OutOfRange_Throws(double degrees, double xPpm, double yPpm)
    {
        var calibration = new AxisCalibration { SquarenessDegrees = degrees, ScaleXPpm = xPpm, ScaleYPpm = yPpm };

        Assert.Throws<CalibrationException>(() => calibration.Validate());
    }
}
