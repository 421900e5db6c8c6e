namespace LaserEngrave.Core.Marks;

/// <summary>The two-dimensional codes a mark can be.</summary>
public enum CodeKind
{
    /// <summary>A QR code (QRCoder), error correction L, M, Q or H.</summary>
    Qr,

    /// <summary>A square ECC 200 Data Matrix (ZXing.Net), whose error correction is fixed by its size.</summary>
    DataMatrix,
}
