using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

/// <summary>The one place for a factor of a thousand gives, to the last bit, what the expressions it replaced gave.</summary>
public class UnitsTests
{
    // Values whose thousandths round differently as x / 1000 and x * 0.001, and ordinary ones.
    public static TheoryData<double> Values => [0.1, 0.9, 13, 1.7, 3, 12.5, 0.09921875, 59.999, 123456.789, 1e-9, -4.2];

    [Theory]
    [MemberData(nameof(Values))]
    public void Conversions_AnyValue_BitForBitThePlainExpression(double x)
    {
        Assert.Equal(BitConverter.DoubleToInt64Bits(x * 1000), BitConverter.DoubleToInt64Bits(Units.MmToUm(x)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(x / 1000), BitConverter.DoubleToInt64Bits(Units.UmToMm(x)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(x / 1000), BitConverter.DoubleToInt64Bits(Units.MsToSeconds(x)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(x * 1000), BitConverter.DoubleToInt64Bits(Units.SecondsToMs(x)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(x * 0.09921875 / 1000), BitConverter.DoubleToInt64Bits(Units.StepsToMm(x, 0.09921875)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(x * 1000 / 0.09921875), BitConverter.DoubleToInt64Bits(Units.MmToSteps(x, 0.09921875)));
        Assert.Equal(BitConverter.DoubleToInt64Bits(Units.MmToSteps(x, 0.09921875)), BitConverter.DoubleToInt64Bits(StageUnits.MmToMicrosteps(x, 0.09921875)));
    }

    [Fact]
    public void UmToMm_Thirteen_DividesRatherThanMultipliesByAThousandth()
    {
        // 13 * 0.001 is 0.013000000000000001; the quotient is the nearest double to 0.013, as every caller had it.
        Assert.Equal(0.013, Units.UmToMm(13));
        Assert.NotEqual(13 * 0.001, Units.UmToMm(13));
    }

    [Fact]
    public void StepsToMm_AModuleOfAQrCode_IsItsLengthInMm()
    {
        Assert.Equal(2.5, Units.StepsToMm(25, 100));
        Assert.Equal(25, Units.MmToSteps(2.5, 100));
    }
}
