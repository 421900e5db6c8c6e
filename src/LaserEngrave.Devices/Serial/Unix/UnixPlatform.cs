namespace LaserEngrave.Devices.Serial.Unix;

/// <summary>The numbers that differ between Linux and macOS: open flags, ioctls, errno, termios layout and bits, baud codes.</summary>
/// <remarks>
/// struct termios is treated as an opaque buffer (<see cref="TermiosBufferSize"/> bytes, larger than either OS's)
/// filled by tcgetattr and cfmakeraw; only c_iflag and c_cflag are edited, at the offsets below.
/// Linux: glibc/musl on x86-64 and arm64 (tcflag_t = 32 bits, c_cflag at 8, 60-byte struct).
/// macOS: tcflag_t = unsigned long (64 bits), c_cflag at 16, 72-byte struct.
/// </remarks>
internal abstract class UnixPlatform
{
    public const int TermiosBufferSize = 256;

    public const short PollIn = 0x001;
    public const short PollOut = 0x004;
    public const short PollErr = 0x008;
    public const short PollHangUp = 0x010;
    public const short PollInvalid = 0x020;

    public const int LockExclusive = 2;
    public const int LockNonBlocking = 4;

    public const int TcsaNow = 0;

    public const int ErrNoEntry = 2;
    public const int ErrInterrupted = 4;
    public const int ErrIo = 5;
    public const int ErrNoDeviceOrAddress = 6;
    public const int ErrAccess = 13;
    public const int ErrBusy = 16;
    public const int ErrNoDevice = 19;
    public const int ErrIsDirectory = 21;
    public const int ErrNotTty = 25;
    public const int ErrPermission = 1;

    public static UnixPlatform Current { get; } = OperatingSystem.IsMacOS() ? new MacPlatform() : new LinuxPlatform();

    public abstract int OpenFlags { get; }

    public abstract nuint IoctlExclusive { get; }

    public abstract nuint IoctlCloseOnExec { get; }

    public abstract int FlushBoth { get; }

    public abstract int ErrAgain { get; }

    public abstract ulong CSize { get; }

    public abstract ulong CStopB { get; }

    public abstract ulong CRead { get; }

    public abstract ulong ParEnb { get; }

    public abstract ulong ParOdd { get; }

    public abstract ulong CLocal { get; }

    public abstract ulong CRtsCts { get; }

    public abstract ulong IXon { get; }

    public abstract ulong IXoff { get; }

    protected abstract int IflagOffset { get; }

    protected abstract int CflagOffset { get; }

    protected abstract int FlagBytes { get; }

    /// <summary>The CSn bits for 5 to 8 data bits.</summary>
    public abstract ulong CharacterSize(int dataBits);

    /// <summary>Sets both speeds in the termios buffer; false when the OS has no code for this rate.</summary>
    public abstract unsafe bool TrySetSpeed(byte* termios, int baudRate);

    /// <summary>The rates this OS accepts, for the error message.</summary>
    public abstract string SupportedRates { get; }

    public unsafe ulong ReadIflag(byte* termios) => ReadFlag(termios, IflagOffset);

    public unsafe void WriteIflag(byte* termios, ulong value) => WriteFlag(termios, IflagOffset, value);

    public unsafe ulong ReadCflag(byte* termios) => ReadFlag(termios, CflagOffset);

    public unsafe void WriteCflag(byte* termios, ulong value) => WriteFlag(termios, CflagOffset, value);

    // tcflag_t is a native-endian integer of FlagBytes bytes.
    private unsafe ulong ReadFlag(byte* termios, int offset) =>
        FlagBytes == 8 ? *(ulong*)(termios + offset) : *(uint*)(termios + offset);

    private unsafe void WriteFlag(byte* termios, int offset, ulong value)
    {
        if (FlagBytes == 8)
        {
            *(ulong*)(termios + offset) = value;
        }
        else
        {
            *(uint*)(termios + offset) = (uint)value;
        }
    }

    private sealed class LinuxPlatform : UnixPlatform
    {
        // Linux encodes rates as Bnnn codes (asm-generic/termbits.h); only these rates can be set through cfsetispeed.
        private static readonly Dictionary<int, uint> BaudCodes = new()
        {
            [50] = 1, [75] = 2, [110] = 3, [134] = 4, [150] = 5, [200] = 6, [300] = 7, [600] = 8, [1200] = 9,
            [1800] = 10, [2400] = 11, [4800] = 12, [9600] = 13, [19200] = 14, [38400] = 15,
            [57600] = 0x1001, [115200] = 0x1002, [230400] = 0x1003, [460800] = 0x1004, [500000] = 0x1005,
            [576000] = 0x1006, [921600] = 0x1007, [1000000] = 0x1008, [1152000] = 0x1009, [1500000] = 0x100A,
            [2000000] = 0x100B, [2500000] = 0x100C, [3000000] = 0x100D, [3500000] = 0x100E, [4000000] = 0x100F,
        };

        // O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC
        public override int OpenFlags => 0x2 | 0x100 | 0x800 | 0x80000;

        public override nuint IoctlExclusive => 0x540C;

        public override nuint IoctlCloseOnExec => 0x5451;

        public override int FlushBoth => 2;

        public override int ErrAgain => 11;

        public override ulong CSize => 0x30;

        public override ulong CStopB => 0x40;

        public override ulong CRead => 0x80;

        public override ulong ParEnb => 0x100;

        public override ulong ParOdd => 0x200;

        public override ulong CLocal => 0x800;

        public override ulong CRtsCts => 0x80000000;

        public override ulong IXon => 0x400;

        public override ulong IXoff => 0x1000;

        public override string SupportedRates => string.Join(", ", BaudCodes.Keys);

        protected override int IflagOffset => 0;

        protected override int CflagOffset => 8;

        protected override int FlagBytes => 4;

        public override ulong CharacterSize(int dataBits) => (ulong)(dataBits - 5) << 4;

        public override unsafe bool TrySetSpeed(byte* termios, int baudRate)
        {
            if (!BaudCodes.TryGetValue(baudRate, out var code))
            {
                return false;
            }

            return LibC.CfSetInputSpeedLinux(termios, code) == 0 && LibC.CfSetOutputSpeedLinux(termios, code) == 0;
        }
    }

    private sealed class MacPlatform : UnixPlatform
    {
        // O_RDWR | O_NONBLOCK | O_NOCTTY | O_CLOEXEC
        public override int OpenFlags => 0x2 | 0x4 | 0x20000 | 0x1000000;

        // _IO('t', 13) and _IO('f', 1)
        public override nuint IoctlExclusive => 0x2000740D;

        public override nuint IoctlCloseOnExec => 0x20006601;

        public override int FlushBoth => 3;

        public override int ErrAgain => 35;

        public override ulong CSize => 0x300;

        public override ulong CStopB => 0x400;

        public override ulong CRead => 0x800;

        public override ulong ParEnb => 0x1000;

        public override ulong ParOdd => 0x2000;

        public override ulong CLocal => 0x8000;

        // CCTS_OFLOW | CRTS_IFLOW
        public override ulong CRtsCts => 0x30000;

        public override ulong IXon => 0x200;

        public override ulong IXoff => 0x400;

        public override string SupportedRates => "the standard rates up to 230400";

        protected override int IflagOffset => 0;

        protected override int CflagOffset => 16;

        protected override int FlagBytes => 8;

        public override ulong CharacterSize(int dataBits) => (ulong)(dataBits - 5) << 8;

        // macOS's speed_t is the rate itself; the driver refuses the ones it cannot do.
        public override unsafe bool TrySetSpeed(byte* termios, int baudRate) =>
            LibC.CfSetInputSpeedMac(termios, (nuint)baudRate) == 0 && LibC.CfSetOutputSpeedMac(termios, (nuint)baudRate) == 0;
    }
}
