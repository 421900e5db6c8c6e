using LaserEngrave.Wire.Zaber;


namespace LaserEngrave.Wire.Tests.Zaber;

public class ZaberFrameTests
{
    [Fact]
    public void Encode_MoveRelativeMinusOne_MatchesManual()
    {
        // Manual example: device 2 move relative -1 -> 2,21,255,255,255,255.
        Assert.Equal(new byte[] { 2, 21, 255, 255, 255, 255 }, new ZaberFrame(2, ZaberCommand.MoveRelative, -1).ToBytes());
    }

    [Fact]
    public void Encode_MoveAbsolute257_MatchesManual()
    {
        Assert.Equal(new byte[] { 1, 20, 1, 1, 0, 0 }, new ZaberFrame(1, ZaberCommand.MoveAbsolute, 257).ToBytes());
    }

    [Theory]
    [InlineData(0)]
    [InlineData(604724)]
    [InlineData(-604724)]
    [InlineData(int.MinValue)]
    [InlineData(int.MaxValue)]
    public void Decode_InvertsEncode_Signed(int data)
    {
        var frame = new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, data);
        Assert.Equal(frame, ZaberFrame.Decode(frame.ToBytes()));
    }
}
