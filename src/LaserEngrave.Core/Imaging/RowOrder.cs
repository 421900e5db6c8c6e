namespace LaserEngrave.Core.Imaging;

/// <summary>The order in which a file stores its pixel rows.</summary>
public enum RowOrder
{
    /// <summary>The first stored row is the top of the image (PNG, GIF, Netpbm, BMP with a negative height).</summary>
    TopDown,

    /// <summary>The first stored row is the bottom of the image (BMP with a positive height).</summary>
    BottomUp,
}
